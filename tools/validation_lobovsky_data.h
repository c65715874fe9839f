// Water levels of Lobovsky, Botia-Vera, Castellana, Mas-Soler & Souto-Iglesias (2014),
// "Experimental investigation of dynamic pressure loads during dam break", J. Fluids Struct.
// 48:407-434, Fig. 16: a column H = 0.3 m high and 2H long released in a tank 1.61 m long
// (5.367 H: the layout of Buchner 2002 and Marrone et al. 2011 at half scale), the water level
// h/H at four gauges against T = t sqrt(g/H). The curves as digitised in TNL-SPH
// (github.com/TNL-Project/TNL-SPH, examples/resources/damBreak2D/
// damBreak2D_experimentalDataLobovsky2014/waterLevel/Fig16_WaterLevels_*.dat, MIT licence,
// (c) 2022-2023 Tomas Halada), two repeated records per gauge ("ETSIN 01" and "02") but H1's
// one; their gauge positions (the same repository's measuretool configuration) agree with a
// second, independent digitisation (XCALibre.jl's ref_data, gauges at 0.3, 1.114, 1.362 m) to
// 0.01 in h/H. Here each record is resampled every 0.1 in T (linearly), the records averaged,
// and half their difference kept as the experiment's repeatability.
#pragma once

namespace talus::validation::lobovsky {

/// Gauge positions over H from the reservoir's back wall (0.3, 0.865, 1.114, 1.3625 m at H = 0.3 m).
constexpr double kGaugeX[4] = {1.0, 2.883333, 3.713333, 4.541667};
constexpr double kStepT = 0.1;  ///< sample spacing in T
constexpr int kSamples = 53;    ///< T = 0 ... 5.2, before the wave reflected by the far wall returns

/// Mean of the records, h/H, per gauge and sample.
constexpr double kLevel[4][kSamples] = {
  {// H1
    1.000, 0.999, 0.996, 0.991, 0.989, 0.982, 0.975, 0.969, 0.953, 0.946, 0.931, 0.916, 0.897, 0.884,
    0.870, 0.854, 0.838, 0.825, 0.811, 0.797, 0.783, 0.767, 0.754, 0.737, 0.719, 0.705, 0.688, 0.678,
    0.664, 0.645, 0.632, 0.621, 0.605, 0.590, 0.577, 0.568, 0.555, 0.540, 0.528, 0.515, 0.500, 0.490,
    0.479, 0.472, 0.460, 0.452, 0.442, 0.434, 0.425, 0.414, 0.402, 0.392, 0.385},
  {// H2
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.011, 0.063, 0.117, 0.152,
    0.168, 0.187, 0.198, 0.209, 0.211, 0.213, 0.214, 0.214, 0.216, 0.224, 0.231, 0.239, 0.241, 0.250,
    0.254, 0.257, 0.260, 0.265, 0.267, 0.269, 0.272, 0.275, 0.279, 0.282, 0.284, 0.288, 0.290, 0.292,
    0.293, 0.295, 0.295, 0.297, 0.296, 0.293, 0.295, 0.294, 0.294, 0.293, 0.293},
  {// H3
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.047, 0.099, 0.133, 0.149, 0.155, 0.156, 0.159, 0.159, 0.159, 0.157, 0.158,
    0.159, 0.165, 0.171, 0.178, 0.182, 0.186, 0.193, 0.198, 0.203, 0.207, 0.215, 0.222, 0.225, 0.227,
    0.229, 0.230, 0.230, 0.233, 0.236, 0.237, 0.237, 0.237, 0.241, 0.241, 0.240},
  {// H4
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.038, 0.080, 0.106, 0.121, 0.129, 0.132,
    0.133, 0.135, 0.135, 0.135, 0.136, 0.135, 0.136, 0.136, 0.141, 0.147, 0.150, 0.153, 0.156, 0.161,
    0.167, 0.172, 0.177, 0.184, 0.189, 0.192, 0.200, 0.206, 0.211, 0.214, 0.215},
};
/// Half the difference of the two records (0 at H1, one record).
constexpr double kSpread[4][kSamples] = {
  {// H1
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000},
  {// H2
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.011, 0.007, 0.005,
    0.009, 0.002, 0.003, 0.002, 0.002, 0.003, 0.002, 0.003, 0.005, 0.007, 0.011, 0.008, 0.008, 0.007,
    0.009, 0.007, 0.005, 0.004, 0.004, 0.005, 0.003, 0.002, 0.003, 0.002, 0.004, 0.002, 0.002, 0.002,
    0.002, 0.002, 0.004, 0.002, 0.001, 0.004, 0.004, 0.003, 0.004, 0.002, 0.001},
  {// H3
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.007, 0.002, 0.001, 0.003, 0.001, 0.003, 0.004, 0.005, 0.005, 0.004, 0.005,
    0.004, 0.001, 0.002, 0.003, 0.002, 0.002, 0.002, 0.001, 0.000, 0.000, 0.000, 0.005, 0.007, 0.006,
    0.003, 0.004, 0.002, 0.002, 0.000, 0.001, 0.001, 0.000, 0.000, 0.000, 0.001},
  {// H4
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000,
    0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000, 0.013, 0.008, 0.007, 0.006, 0.005,
    0.003, 0.003, 0.003, 0.003, 0.005, 0.004, 0.003, 0.004, 0.005, 0.007, 0.009, 0.007, 0.006, 0.007,
    0.008, 0.006, 0.003, 0.003, 0.006, 0.007, 0.007, 0.006, 0.004, 0.004, 0.004},
};

/// Pressure sensors on the far wall, at z/H (3, 15, 30 and 80 mm at H = 0.3 m; the last at
/// Buchner's P1, 0.2592 H), and P = p / (rho g H) averaged over 3.5 <= T <= 5 from the records
/// of one run ("peak event 5", Fig. 18, as digitised in the same repository's pressure/ folder).
/// At 15 mm two sensors side by side read 0.661 and 0.522: the mean is given, and half their
/// difference (0.07) is the spread across the wall's width. One run: the impact peaks scatter
/// from run to run (Lobovsky et al. report their statistics over 100), the plateau much less.
constexpr double kSensorZ[4] = {0.01, 0.05, 0.1, 0.266667};
constexpr double kSensorPlateau[4] = {0.681, 0.592, 0.589, 0.537};

} // namespace talus::validation::lobovsky
