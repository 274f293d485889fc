#pragma once
// The point dimensions for which the curve templates are compiled (explicit instantiation in
// the .cpp files, so headers stay declarations only): 1 (scalar polynomials), 2, 3, and 4
// (homogeneous coordinates of rational 3D curves).

#define PATCHWORK_FOR_EACH_CURVE_DIM(X) X(1) X(2) X(3) X(4)
