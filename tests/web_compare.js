// web_compare.js REFERENCE SHOT - compares the coarse features of two pictures of the demo's view
// (600 x 330 PNG: the native demo's --png-plain picture and the browser's canvas): each is cut
// into 10 x 10 pixel cells, a cell is occupied when at least half its pixels show a particle
// (neither background: white in the native picture, dark in the page), and the pictures match
// when the cells occupied in one but not the other are at most 3 % of the cells occupied in
// either. Why 3 %: a 0.24 m block is 72 px across, about 50 cells; one block shifted by a
// quarter of its side flips about 25 of the ~800 occupied cells of the 600-frame scene, so a
// misplaced block fails, while the cells along the edges cannot flip unless positions differ.
// Node's own modules only (zlib); prints the figures; exit status 1 when they do not match.
'use strict';
const fs = require('fs');
const zlib = require('zlib');

const CELL = 10, MAX_MISMATCH = 0.03;

// A PNG's RGB pixels: 8-bit depth, colour type 2 (RGB), 3 (indexed) or 6 (RGBA), not interlaced.
function readPng(file) {
  const data = fs.readFileSync(file);
  let at = 8, width = 0, height = 0, type = 0, palette = null;
  const idat = [];
  while (at < data.length) {
    const length = data.readUInt32BE(at), kind = data.toString('latin1', at + 4, at + 8), body = data.subarray(at + 8, at + 8 + length);
    if (kind === 'IHDR') {
      width = body.readUInt32BE(0); height = body.readUInt32BE(4); type = body[9];
      if (body[8] !== 8 || body[12] !== 0 || ![2, 3, 6].includes(type)) throw new Error(file + ': not an 8-bit RGB, RGBA or indexed PNG');
    }
    if (kind === 'PLTE') palette = body;
    if (kind === 'IDAT') idat.push(body);
    at += 12 + length;
  }
  const raw = zlib.inflateSync(Buffer.concat(idat)), bpp = type === 6 ? 4 : type === 2 ? 3 : 1, stride = width * bpp;
  const rows = Buffer.alloc(stride * height);
  for (let y = 0; y < height; ++y) { // undo the row filters (PNG spec, section 9)
    const filter = raw[y * (stride + 1)], src = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= bpp ? rows[y * stride + x - bpp] : 0, b = y ? rows[(y - 1) * stride + x] : 0;
      const c = x >= bpp && y ? rows[(y - 1) * stride + x - bpp] : 0;
      const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
      const predictor = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][filter];
      rows[y * stride + x] = (src[x] + predictor) & 255;
    }
  }
  const rgb = Buffer.alloc(width * height * 3);
  for (let k = 0; k < width * height; ++k)
    for (let m = 0; m < 3; ++m) rgb[3 * k + m] = type === 3 ? palette[3 * rows[k] + m] : rows[k * bpp + m];
  return { width, height, rgb };
}

// The occupied cells of a picture, as a string of 0 and 1.
function cells(picture) {
  const { width, height, rgb } = picture, columns = Math.floor(width / CELL), lines = Math.floor(height / CELL);
  let out = '';
  for (let cy = 0; cy < lines; ++cy)
    for (let cx = 0; cx < columns; ++cx) {
      let particles = 0;
      for (let y = cy * CELL; y < (cy + 1) * CELL; ++y)
        for (let x = cx * CELL; x < (cx + 1) * CELL; ++x) {
          const r = rgb[3 * (y * width + x)], g = rgb[3 * (y * width + x) + 1], b = rgb[3 * (y * width + x) + 2];
          const background = (r === 255 && g === 255 && b === 255) || (r === 16 && g === 18 && b === 28);
          particles += !background;
        }
      out += particles * 2 >= CELL * CELL ? '1' : '0';
    }
  return out;
}

const [referenceFile, shotFile] = process.argv.slice(2);
const reference = readPng(referenceFile), shot = readPng(shotFile);
if (reference.width !== shot.width || reference.height !== shot.height) {
  console.log(`web_compare: the pictures differ in size: ${reference.width} x ${reference.height} and ${shot.width} x ${shot.height}`);
  process.exit(1);
}
const a = cells(reference), b = cells(shot);
let either = 0, mismatch = 0;
for (let k = 0; k < a.length; ++k) { either += a[k] === '1' || b[k] === '1'; mismatch += a[k] !== b[k]; }
const fraction = either ? mismatch / either : 1;
console.log(`web_compare: occupied cells (${CELL} px) reference ${a.split('1').length - 1}, browser ${b.split('1').length - 1}, ` +
  `in one only ${mismatch} = ${(100 * fraction).toFixed(1)} % of ${either} (allowed ${100 * MAX_MISMATCH} %)`);
process.exit(fraction <= MAX_MISMATCH ? 0 : 1);
