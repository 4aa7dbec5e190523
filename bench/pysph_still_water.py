"""PySPH's hydrostatic tank, measured like bench/still_water.c (called by pysph_still_water.sh).

  python3 pysph_still_water.py run  DEPTH_OVER_DP OUTDIR   run PySPH's own example, t = 0..10 s
  python3 pysph_still_water.py post DEPTH_OVER_DP OUTDIR WALL_S   read its output, print RESULT

The example (pysph.examples.hydrostatic_tank) is run as shipped: its defaults are depth/dp 45
(H = 0.9, dx = 0.02). For another depth/dp only its module-level resolution constants are
rescaled before it builds the particles (dx, ghost extent, dt with each limit scaled as its
formula scales with h); the scheme and everything else stays PySPH's.

Metric as in still_water.c: the fluid's speeds are read at every output (about every 0.05 s);
for each second (k-1, k] the RMS over the outputs and particles and the largest speed, in units
of sqrt(g H); the worst of the seconds 6..10 (i.e. 5 s to 10 s) is reported."""
import glob
import json
import math
import os
import sys


def run(depth_over_dp, outdir):
    import pysph.examples.hydrostatic_tank as ht
    if depth_over_dp != round(ht.H / ht.dx):  # rescale the example's resolution constants
        r = (ht.H / depth_over_dp) / ht.dx    # new dx / old dx
        ht.dx *= r
        ht.nx = round(ht.Lx / ht.dx)
        ht.ghost_extent *= r
        ht.h0 *= r
        ht.dt_cfl *= r                        # 0.25 h / (c0 + Vmax)
        ht.dt_viscous *= r * r                # 0.125 h^2 / nu
        ht.dt_force *= math.sqrt(r)           # 0.25 sqrt(h / g)
        ht.dt = 0.75 * min(ht.dt_cfl, ht.dt_viscous, ht.dt_force)
    pfreq = max(1, int(0.05 / ht.dt))         # an output at least every 0.05 s (>= 20 per second)
    print("# example: %s  H=%g Lx=%g dx=%g h/dx=%g c0=%g g=%g dt=%g pfreq=%d" % (
        ht.__file__, ht.H, ht.Lx, ht.dx, ht.hdx, ht.c0, abs(ht.gy), ht.dt, pfreq), flush=True)
    app = ht.HydrostaticTank(fname='hydrostatic_tank')
    app.run(['--tf', '10', '--pfreq', str(pfreq), '--no-openmp', '-d', outdir])


def post(depth_over_dp, outdir, wall_s):
    import pysph.examples.hydrostatic_tank as ht
    from pysph.solver.utils import get_files, iter_output
    u_ref = math.sqrt(abs(ht.gy) * ht.H)      # sqrt(g H) of the example (g = 1, H = 0.9)
    rms2_sum, samples, vmax = {}, {}, {}
    nfluid = 0
    for sd, fluid in iter_output(get_files(outdir, 'hydrostatic_tank'), 'fluid'):
        t = float(sd['t'])
        if t <= 1e-9:
            continue
        s2 = fluid.u ** 2 + fluid.v ** 2
        nfluid = s2.size
        k = int(math.ceil(t - 1e-9))          # second (k-1, k]
        rms2_sum[k] = rms2_sum.get(k, 0.0) + s2.mean()
        samples[k] = samples.get(k, 0) + 1
        vmax[k] = max(vmax.get(k, 0.0), math.sqrt(s2.max()))
    print("# second  outputs  rms/sqrt(gH)  max/sqrt(gH)")
    worst_rms = worst_max = 0.0
    for k in sorted(samples):
        brms = math.sqrt(rms2_sum[k] / samples[k]) / u_ref
        bmax = vmax[k] / u_ref
        print("%8d  %7d  %12.3e  %12.3e" % (k, samples[k], brms, bmax))
        if 5 < k <= 10:
            worst_rms, worst_max = max(worst_rms, brms), max(worst_max, bmax)
    info = glob.glob(os.path.join(outdir, '*.info'))
    solve_s = json.load(open(info[0])).get('cpu_time', float('nan')) if info else float('nan')
    print("RESULT case=pysph_still_water depth_over_dp=%d worst_rms=%.3e worst_max=%.3e "
          "(units sqrt(g H)) particles=%d wall_s=%.0f solve_s=%.0f" % (
              depth_over_dp, worst_rms, worst_max, nfluid, wall_s, solve_s))


if __name__ == '__main__':
    if sys.argv[1] == 'run':
        run(int(sys.argv[2]), sys.argv[3])
    else:
        post(int(sys.argv[2]), sys.argv[3], float(sys.argv[4]))
