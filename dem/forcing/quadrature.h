// Quadrature over a convex polygon, for the skin and air drag integrals (paper Eq. 13-14 integrated over the
// bottom and top faces). The polygon is split into a fan of triangles from its centroid; each triangle is
// integrated with a symmetric rule exact for polynomials of the stated degree (degree 1: centroid; degree 2: edge
// midpoints; degree 4: Dunavant's 6 points; degree 5: Radon's 7 points). `centroid` is the paper's form: one
// point at the polygon's centroid carrying the whole area.
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::forcing {

using geometry::Vec2;

enum class Quadrature {
  centroid,  // 1 point per polygon (exact for degree 1)
  degree1,   // 1 point per fan triangle (its centroid)
  degree2,   // the edge midpoints of each triangle, the spoke midpoints shared: 2 points per polygon vertex
  degree4,   // 6 points per triangle (Dunavant)
  degree5,   // 7 points per triangle (Radon)
};

std::string_view to_string(Quadrature q);
// Points the rule places in an n-gon.
int quadrature_points(Quadrature q, int polygon_vertices);

struct QuadraturePoint {
  Vec2 point;     // [m], in the frame of the vertices
  double weight;  // area carried [m^2]; the weights sum to the polygon's area
};

// Appends the rule's points for the convex, counter-clockwise polygon `vertices` to `out`.
void polygon_quadrature(std::span<const Vec2> vertices, Quadrature q, std::vector<QuadraturePoint>& out);

}  // namespace polyfloe::forcing
