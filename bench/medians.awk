# medians.awk - the medians of a bench script's interleaved rounds: rows "name variant value
# [value2]" in (one a run), one row a (name, variant) out, "name variant median [median2]", in
# no particular order (the caller sorts). Used by bench/pass_fusion.sh and bench/instancing_cost.sh.
function median(key, col,    m, i, j, x, a) {
    m = n[key]; for (i = 1; i <= m; ++i) a[i] = t[key, i, col]
    for (i = 1; i <= m; ++i) for (j = i + 1; j <= m; ++j) if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
    return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
}
{ key = $1 " " $2; n[key]++; t[key, n[key], 1] = $3; t[key, n[key], 2] = $4 }
END {
    for (key in n) {
        line = key " " median(key, 1)
        if (t[key, 1, 2] != "") line = line " " median(key, 2)
        print line
    }
}
