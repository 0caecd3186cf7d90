# Prints the pull-off table shown by `make figures` from the `coatcontact pulloff` outputs
# (files named .../pulloff_E<ratio>.tsv). Columns are found by name on the "# columns:" line.
# -v etas="0.1 1 10": eta values of the table; the nearest computed eta (in log) is used.
# For each ratio: P at those eta, and the extreme P over all computed eta (most adhesive).

function reset_file() { nrow = 0; delete col }
function flush_file(   i, k, best, j, d, dmin, mode, c, name, line, ext, ext_eta) {
  if (nrow == 0) return
  for (mode = 1; mode <= 2; mode++) {
    c = (mode == 1) ? col["P_load"] : col["P_disp"]
    name = (mode == 1) ? "load" : "displacement"
    line = sprintf("  %7s  %-13s", (mode == 1) ? ratio : "", name)
    for (k = 1; k <= ntable; k++) {
      dmin = 1e300; best = 0
      for (j = 1; j <= nrow; j++) {
        d = log(eta[j] / table_eta[k]); if (d < 0) d = -d
        if (d < dmin) { dmin = d; best = j }
      }
      line = line sprintf("  %9.4f", value[best, c])
    }
    ext = 1e300; ext_eta = 0; top = -1e300
    for (j = 1; j <= nrow; j++) {
      if (value[j, c] < ext) { ext = value[j, c]; ext_eta = eta[j] }
      if (value[j, c] > top) top = value[j, c]
    }
    if (top - ext <= 1e-6 * (top > -top ? top : -top))
      print line "   (independent of eta)"
    else
      print line sprintf("   %9.4f at eta = %.3g", ext, ext_eta)
  }
}
BEGIN {
  ntable = split(etas, table_eta, " ")
  header = sprintf("  %7s  %-13s", "E1/E0", "control")
  for (k = 1; k <= ntable; k++) header = header sprintf("  %9s", "eta=" table_eta[k])
  print "pull-off force P = F/(pi w R)  (JKR, homogeneous: load -1.5, displacement -0.8333)"
  print header "   most adhesive"
  FS = "\t"
}
FNR == 1 {
  flush_file(); reset_file()
  ratio = FILENAME; sub(/^.*pulloff_E/, "", ratio); sub(/\.tsv$/, "", ratio)
}
/^# columns:/ {
  line = $0; sub(/^# columns:[ \t]*/, "", line)
  n = split(line, names, /[ \t]+/)
  for (i = 1; i <= n; i++) col[names[i]] = i
  next
}
/^#/ || NF == 0 { next }
{
  nrow++
  eta[nrow] = $(col["eta"])
  for (i = 1; i <= NF; i++) value[nrow, i] = $i
}
END { flush_file() }
