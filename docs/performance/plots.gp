set terminal pngcairo size 900,600 font ',11'
set output 'error_vs_triangles.png'
set logscale xy
set grid
set key top right
set format y '10^{%L}'
set xlabel 'triangles'
set ylabel 'measured error (two-sided Hausdorff / box diagonal)'
plot 'patchwork_adaptive.dat' using 2:1 with linespoints title 'patchwork adaptive', 'patchwork_uniform.dat' using 2:1 with linespoints title 'patchwork uniform', 'three_js.dat' using 2:1 with linespoints title 'three.js', 'open_cascade.dat' using 2:1 with linespoints title 'Open CASCADE', 'open_cascade_0_5_rad.dat' using 2:1 with linespoints title 'Open CASCADE 0.5 rad'
set terminal pngcairo size 900,600 font ',11'
set output 'error_vs_time.png'
set logscale xy
set grid
set key top right
set format y '10^{%L}'
set xlabel 'seconds (tessellation alone, one thread)'
set ylabel 'measured error (two-sided Hausdorff / box diagonal)'
plot 'patchwork_adaptive.dat' using 3:1 with linespoints title 'patchwork adaptive', 'patchwork_uniform.dat' using 3:1 with linespoints title 'patchwork uniform', 'three_js.dat' using 3:1 with linespoints title 'three.js', 'open_cascade.dat' using 3:1 with linespoints title 'Open CASCADE', 'open_cascade_0_5_rad.dat' using 3:1 with linespoints title 'Open CASCADE 0.5 rad'
set terminal pngcairo size 900,600 enhanced font ',10'
set encoding utf8
set output 'hard_cases.png'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xrange [1:1.0e69]
set yrange [1.0e-19:10]
set xlabel 'cond(p, s) = sum |c_i| B_i^n(s) / |p(s)|' noenhanced
set ylabel 'relative error |computed - p(s)| / |p(s)|, clamped at 1' noenhanced
set key bottom right box opaque
set grid
set samples 500
u = 2.0**-53
n = 40
g(k) = k*u / (1 - k*u)
plot 'hard_cases_seventh_power_horner.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 2 ps 0.6 lc rgb '#7f7f7f' title 'Horner (power)', \
     'hard_cases_cubic_half_horner.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 2 ps 0.6 lc rgb '#7f7f7f' notitle, \
     'hard_cases_twentieths_horner.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 2 ps 0.6 lc rgb '#7f7f7f' notitle, \
     'hard_cases_halvings_horner.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 2 ps 0.6 lc rgb '#7f7f7f' notitle, \
     'hard_cases_degree40_horner.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 2 ps 0.6 lc rgb '#7f7f7f' notitle, \
     'hard_cases_offset_horner.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 2 ps 0.6 lc rgb '#7f7f7f' notitle, \
     'hard_cases_seventh_power_patch_grid.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 3 ps 0.6 lc rgb '#ff7f0e' title 'patch grid', \
     'hard_cases_cubic_half_patch_grid.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 3 ps 0.6 lc rgb '#ff7f0e' notitle, \
     'hard_cases_twentieths_patch_grid.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 3 ps 0.6 lc rgb '#ff7f0e' notitle, \
     'hard_cases_halvings_patch_grid.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 3 ps 0.6 lc rgb '#ff7f0e' notitle, \
     'hard_cases_degree40_patch_grid.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 3 ps 0.6 lc rgb '#ff7f0e' notitle, \
     'hard_cases_offset_patch_grid.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 3 ps 0.6 lc rgb '#ff7f0e' notitle, \
     'hard_cases_seventh_power_patch_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 4 ps 0.6 lc rgb '#9467bd' title 'patch de Casteljau', \
     'hard_cases_cubic_half_patch_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 4 ps 0.6 lc rgb '#9467bd' notitle, \
     'hard_cases_twentieths_patch_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 4 ps 0.6 lc rgb '#9467bd' notitle, \
     'hard_cases_halvings_patch_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 4 ps 0.6 lc rgb '#9467bd' notitle, \
     'hard_cases_degree40_patch_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 4 ps 0.6 lc rgb '#9467bd' notitle, \
     'hard_cases_offset_patch_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 4 ps 0.6 lc rgb '#9467bd' notitle, \
     'hard_cases_seventh_power_batch_table.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 1 ps 0.6 lc rgb '#2ca02c' title 'batch (table)', \
     'hard_cases_cubic_half_batch_table.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 1 ps 0.6 lc rgb '#2ca02c' notitle, \
     'hard_cases_twentieths_batch_table.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 1 ps 0.6 lc rgb '#2ca02c' notitle, \
     'hard_cases_halvings_batch_table.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 1 ps 0.6 lc rgb '#2ca02c' notitle, \
     'hard_cases_degree40_batch_table.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 1 ps 0.6 lc rgb '#2ca02c' notitle, \
     'hard_cases_offset_batch_table.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 1 ps 0.6 lc rgb '#2ca02c' notitle, \
     'hard_cases_seventh_power_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 6 ps 0.6 lc rgb '#1f77b4' title 'de Casteljau', \
     'hard_cases_cubic_half_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 6 ps 0.6 lc rgb '#1f77b4' notitle, \
     'hard_cases_twentieths_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 6 ps 0.6 lc rgb '#1f77b4' notitle, \
     'hard_cases_halvings_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 6 ps 0.6 lc rgb '#1f77b4' notitle, \
     'hard_cases_degree40_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 6 ps 0.6 lc rgb '#1f77b4' notitle, \
     'hard_cases_offset_de_casteljau.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 6 ps 0.6 lc rgb '#1f77b4' notitle, \
     'hard_cases_seventh_power_compensated.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 7 ps 0.6 lc rgb '#d62728' title 'compensated', \
     'hard_cases_cubic_half_compensated.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 7 ps 0.6 lc rgb '#d62728' notitle, \
     'hard_cases_twentieths_compensated.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 7 ps 0.6 lc rgb '#d62728' notitle, \
     'hard_cases_halvings_compensated.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 7 ps 0.6 lc rgb '#d62728' notitle, \
     'hard_cases_degree40_compensated.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 7 ps 0.6 lc rgb '#d62728' notitle, \
     'hard_cases_offset_compensated.dat' using 1:($2 > 0 ? $2 : 1.0e-18) with points pt 7 ps 0.6 lc rgb '#d62728' notitle, \
     u*x with lines lw 2 dt 2 lc rgb 'black' title 'u·cond', \
     g(2*n)*x with lines lw 2 lc rgb '#1f77b4' title 'γ_{2n}·cond, n = 40', \
     u + 2*g(3*n)**2*x with lines lw 2 lc rgb '#d62728' title 'u + 2γ_{3n}^2·cond, n = 40'
set terminal pngcairo size 900,600 font ',11'
set output 'scale.png'
set logscale xy
set xrange [16:65536]
set yrange [0.00200515:16.6583]
set y2range [2.36339:2227.4]
set xlabel 'patches'
set ylabel 'seconds'
set y2label 'peak memory, MB'
set logscale y2
set ytics nomirror
set y2tics
set key left top
set grid
plot 'scale.dat' using 1:2 with linespoints title 'whole process, seconds', x * 0.000131705 with lines dt 2 title 'linear (seconds)', 'scale.dat' using 1:3 axes x1y2 with linespoints title 'peak memory, MB', x * 0.068544 axes x1y2 with lines dt 3 title 'linear (MB)'
