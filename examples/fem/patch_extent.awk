# Patch extent from railwear's pressure CSV (`railwear contact SCENE --csv FILE`): the half-length
# along x and the half-width along the arc s of the cells in contact (p > 0), to the outer edge
# of the outermost cell (max |x| + dx/2, max |s| + ds/2; the true edge lies within +-half a
# cell of it). Used by the comparison table of docs/fem_contact_cases.md:
#   awk -F, -f examples/fem/patch_extent.awk pressure.csv
# Columns: patch,ix,js,x_mm,s_mm,y_mm,z_mm,p_MPa (one patch expected).
NR == 1 { next }
{
  x = $4 + 0; s = $5 + 0; p = $8 + 0
  if ($2 == 0 && $3 == 0) { x0 = x; s0 = s }
  if ($2 == 1 && $3 == 0) dx = x - x0
  if ($2 == 0 && $3 == 1) ds = s - s0
  if (p > 0) {
    ax = x < 0 ? -x : x; as = s < 0 ? -s : s
    if (ax > X) X = ax
    if (as > S) S = as
    n++
  }
}
END {
  printf "half_length_x_mm %.3f  half_width_s_mm %.3f  (cells %d, dx %.4f mm, ds %.4f mm)\n", X + dx / 2, S + ds / 2, n, dx, ds
}
