set terminal svg size 1200,560 dynamic noenhanced
set output 'error_alpha.svg.tmp-mfv'
reset
set logscale y
set format y '1e%L'
set key outside right
set ylabel 'ulps vs double reference'
set yrange [1e-2:1e13]
set title 'largest error over theta, per alpha, float32'
set logscale x
set format x '1e%L'
set xlabel 'alpha (shared width)'
plot 'error_alpha.dat' index 0 using 1:2 with linespoints lc rgb '#000000' title 'D phong', 'error_alpha.dat' index 1 using 1:2 with linespoints lc rgb '#e69f00' title 'D beckmann', 'error_alpha.dat' index 2 using 1:2 with linespoints lc rgb '#56b4e9' title 'D ggx', 'error_alpha.dat' index 3 using 1:2 with linespoints lc rgb '#009e73' title 'D blinn_rho', 'error_alpha.dat' index 4 using 1:2 with linespoints lc rgb '#f0e442' title 'D beckmann_ct82', 'error_alpha.dat' index 5 using 1:2 with linespoints lc rgb '#0072b2' title 'G1 smith_beckmann_approx', 'error_alpha.dat' index 6 using 1:2 with linespoints lc rgb '#d55e00' title 'G1 smith_beckmann', 'error_alpha.dat' index 7 using 1:2 with linespoints lc rgb '#cc79a7' title 'G1 smith_phong', 'error_alpha.dat' index 8 using 1:2 with linespoints lc rgb '#7f7f7f' title 'G1 smith_ggx', 'error_alpha.dat' index 9 using 1:2 with linespoints lc rgb '#8c564b' title 'D aniso_ggx', 'error_alpha.dat' index 10 using 1:2 with linespoints lc rgb '#17becf' title 'D aniso_beckmann', 'error_alpha.dat' index 11 using 1:2 with linespoints lc rgb '#9467bd' title 'G1 smith_aniso_ggx', 'error_alpha.dat' index 12 using 1:2 with linespoints lc rgb '#000000' title 'G1 smith_aniso_beckmann', 'error_alpha.dat' index 13 using 1:2 with linespoints lc rgb '#e69f00' title 'variant D_ggx via tan2', 'error_alpha.dat' index 14 using 1:2 with linespoints lc rgb '#56b4e9' title 'variant D_ggx via (n.h)^2(a^2-1)+1', 'error_alpha.dat' index 15 using 1:2 with linespoints lc rgb '#009e73' title 'variant D_ggx via |n x h|^2', 'error_alpha.dat' index 16 using 1:2 with linespoints lc rgb '#f0e442' title 'variant Lambda_ggx via tan2', 'error_alpha.dat' index 17 using 1:2 with linespoints lc rgb '#0072b2' title 'variant Lambda_ggx via cos', 'error_alpha.dat' index 18 using 1:2 with linespoints lc rgb '#d55e00' title 'variant Lambda_ggx via x/(2(1+sqrt(1+x)))', 'error_alpha.dat' index 19 using 1:2 with linespoints lc rgb '#cc79a7' title 'variant G1_smith_ggx via Lambda', 'error_alpha.dat' index 20 using 1:2 with linespoints lc rgb '#7f7f7f' title 'variant G1_smith_ggx closed form'
set terminal pngcairo size 1200,560 noenhanced font ',9'
set output 'error_alpha.png.tmp-mfv'
reset
set logscale y
set format y '1e%L'
set key outside right
set ylabel 'ulps vs double reference'
set yrange [1e-2:1e13]
set title 'largest error over theta, per alpha, float32'
set logscale x
set format x '1e%L'
set xlabel 'alpha (shared width)'
plot 'error_alpha.dat' index 0 using 1:2 with linespoints lc rgb '#000000' title 'D phong', 'error_alpha.dat' index 1 using 1:2 with linespoints lc rgb '#e69f00' title 'D beckmann', 'error_alpha.dat' index 2 using 1:2 with linespoints lc rgb '#56b4e9' title 'D ggx', 'error_alpha.dat' index 3 using 1:2 with linespoints lc rgb '#009e73' title 'D blinn_rho', 'error_alpha.dat' index 4 using 1:2 with linespoints lc rgb '#f0e442' title 'D beckmann_ct82', 'error_alpha.dat' index 5 using 1:2 with linespoints lc rgb '#0072b2' title 'G1 smith_beckmann_approx', 'error_alpha.dat' index 6 using 1:2 with linespoints lc rgb '#d55e00' title 'G1 smith_beckmann', 'error_alpha.dat' index 7 using 1:2 with linespoints lc rgb '#cc79a7' title 'G1 smith_phong', 'error_alpha.dat' index 8 using 1:2 with linespoints lc rgb '#7f7f7f' title 'G1 smith_ggx', 'error_alpha.dat' index 9 using 1:2 with linespoints lc rgb '#8c564b' title 'D aniso_ggx', 'error_alpha.dat' index 10 using 1:2 with linespoints lc rgb '#17becf' title 'D aniso_beckmann', 'error_alpha.dat' index 11 using 1:2 with linespoints lc rgb '#9467bd' title 'G1 smith_aniso_ggx', 'error_alpha.dat' index 12 using 1:2 with linespoints lc rgb '#000000' title 'G1 smith_aniso_beckmann', 'error_alpha.dat' index 13 using 1:2 with linespoints lc rgb '#e69f00' title 'variant D_ggx via tan2', 'error_alpha.dat' index 14 using 1:2 with linespoints lc rgb '#56b4e9' title 'variant D_ggx via (n.h)^2(a^2-1)+1', 'error_alpha.dat' index 15 using 1:2 with linespoints lc rgb '#009e73' title 'variant D_ggx via |n x h|^2', 'error_alpha.dat' index 16 using 1:2 with linespoints lc rgb '#f0e442' title 'variant Lambda_ggx via tan2', 'error_alpha.dat' index 17 using 1:2 with linespoints lc rgb '#0072b2' title 'variant Lambda_ggx via cos', 'error_alpha.dat' index 18 using 1:2 with linespoints lc rgb '#d55e00' title 'variant Lambda_ggx via x/(2(1+sqrt(1+x)))', 'error_alpha.dat' index 19 using 1:2 with linespoints lc rgb '#cc79a7' title 'variant G1_smith_ggx via Lambda', 'error_alpha.dat' index 20 using 1:2 with linespoints lc rgb '#7f7f7f' title 'variant G1_smith_ggx closed form'
