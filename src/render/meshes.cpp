#include "render/meshes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace coinroll::render {

namespace {

// push_back rather than insert(end, {...}): GCC 12 misreports the latter (-Wstringop-overflow).
template <class Vertex>
void append(std::vector<Vertex>& out, std::initializer_list<Vertex> vertices) {
  for (const Vertex& v : vertices) out.push_back(v);
}

void addQuad(std::vector<CoinVertex>& out, const CoinVertex& a, const CoinVertex& b, const CoinVertex& c,
             const CoinVertex& d) {
  // a-b-c-d counter-clockwise seen from the side the normals face.
  append(out, {a, b, c, a, c, d});
}

// One ring of the outer rim in the (r, z) half-plane: where it is and its outward unit normal.
struct RimPoint {
  float r, z, nr, nz;
};

// Rings per quarter-circle fillet: 11.25 degrees apart, so on a 13 mm coin's 6.5 mm fillet the
// polygon strays 0.03 mm from the circle, as little as the 128 facets' 0.011 mm around the rim,
// and the per-vertex normals blend the facets smoothly.
constexpr int kFilletRings = 8;

// The outer rim's profile from the back face's edge (z = -h/2) up to the front face's (z = h/2).
// Sharp (rho = 0): the straight band at r = radius. Rounded: a quarter circle of radius rho about
// (radius - rho, -(h/2 - rho)), the straight band up to z = h/2 - rho (none when rho = h/2), and
// the quarter circle about (radius - rho, h/2 - rho). The normal of a fillet ring is the torus'.
std::vector<RimPoint> outerRimProfile(const CoinShape& shape) {
  const float halfThickness = 0.5f * shape.thickness, outer = shape.radius, rho = shape.edgeRadius;
  if (!(rho > 0)) return {{outer, -halfThickness, 1, 0}, {outer, halfThickness, 1, 0}};
  const float centreR = outer - rho, centreZ = std::max(0.0f, halfThickness - rho);
  std::vector<RimPoint> profile;
  profile.reserve(2 * kFilletRings + 2);
  // Fillet rings at angles beta (from the +r axis towards +z) in [beta0, beta0 + pi/2] about
  // (centreR, centreZ * side); the ends are set exactly so they meet the faces and the band.
  auto fillet = [&](float side, double beta0, bool skipFirst) {
    for (int k = skipFirst ? 1 : 0; k <= kFilletRings; ++k) {
      const double beta = beta0 + 0.5 * std::numbers::pi * k / kFilletRings;
      const double c = std::cos(beta), s = std::sin(beta);
      RimPoint p{static_cast<float>(centreR + rho * c), static_cast<float>(side * centreZ + rho * s),
                 static_cast<float>(c), static_cast<float>(s)};
      const bool atFace = side < 0 ? k == 0 : k == kFilletRings, atBand = side < 0 ? k == kFilletRings : k == 0;
      if (atFace) p = {centreR, side * halfThickness, 0, side};
      if (atBand) p = {outer, side * centreZ, 1, 0};
      profile.push_back(p);
    }
  };
  fillet(-1, -0.5 * std::numbers::pi, false);
  // rho = h/2: both fillets meet at the mid-plane, where the band would have no height.
  fillet(+1, 0.0, centreZ == 0);
  return profile;
}

}  // namespace

std::vector<CoinVertex> coinTriangles(const CoinShape& shape, int segments) {
  const float halfThickness = 0.5f * shape.thickness;
  const float outer = shape.radius, inner = shape.innerRadius, rho = shape.edgeRadius;
  // The faces are flat out to where the fillets begin; outer - 0 is outer exactly, so a sharp
  // coin's vertices (and pictures) are the same bytes as before fillets existed.
  const float faceOuter = outer - rho;
  const std::vector<RimPoint> rim = outerRimProfile(shape);
  std::vector<CoinVertex> triangles;
  triangles.reserve(static_cast<std::size_t>(segments) * (18 + 6 * (rim.size() - 1)));
  const float front = static_cast<float>(CoinPart::FrontFace), back = static_cast<float>(CoinPart::BackFace);
  const float outerRim = static_cast<float>(CoinPart::OuterRim), innerRim = static_cast<float>(CoinPart::InnerRim);
  for (int i = 0; i < segments; ++i) {
    const double angle0 = 2 * std::numbers::pi * i / segments, angle1 = 2 * std::numbers::pi * (i + 1) / segments;
    const glm::vec2 u0(std::cos(angle0), std::sin(angle0)), u1(std::cos(angle1), std::sin(angle1));
    const glm::vec3 up(0, 0, 1), down(0, 0, -1);
    if (inner > 0) {
      addQuad(triangles, {glm::vec3(inner * u0, halfThickness), up, front},
              {glm::vec3(faceOuter * u0, halfThickness), up, front},
              {glm::vec3(faceOuter * u1, halfThickness), up, front}, {glm::vec3(inner * u1, halfThickness), up, front});
      addQuad(triangles, {glm::vec3(inner * u1, -halfThickness), down, back},
              {glm::vec3(faceOuter * u1, -halfThickness), down, back},
              {glm::vec3(faceOuter * u0, -halfThickness), down, back},
              {glm::vec3(inner * u0, -halfThickness), down, back});
      const glm::vec3 n0(-u0, 0), n1(-u1, 0);
      addQuad(triangles, {glm::vec3(inner * u1, -halfThickness), n1, innerRim},
              {glm::vec3(inner * u0, -halfThickness), n0, innerRim},
              {glm::vec3(inner * u0, halfThickness), n0, innerRim},
              {glm::vec3(inner * u1, halfThickness), n1, innerRim});
    } else {
      const glm::vec3 centreFront(0, 0, halfThickness), centreBack(0, 0, -halfThickness);
      append<CoinVertex>(triangles, {{centreFront, up, front},
                                     {glm::vec3(faceOuter * u0, halfThickness), up, front},
                                     {glm::vec3(faceOuter * u1, halfThickness), up, front}});
      append<CoinVertex>(triangles, {{centreBack, down, back},
                                     {glm::vec3(faceOuter * u1, -halfThickness), down, back},
                                     {glm::vec3(faceOuter * u0, -halfThickness), down, back}});
    }
    // The outer rim, ring by ring from the back face's edge up to the front face's: each quad
    // runs up the profile, so it winds counter-clockwise seen from outside like the straight band.
    for (std::size_t k = 0; k + 1 < rim.size(); ++k) {
      const RimPoint& p = rim[k];
      const RimPoint& q = rim[k + 1];
      addQuad(triangles, {glm::vec3(p.r * u0, p.z), glm::vec3(p.nr * u0, p.nz), outerRim},
              {glm::vec3(p.r * u1, p.z), glm::vec3(p.nr * u1, p.nz), outerRim},
              {glm::vec3(q.r * u1, q.z), glm::vec3(q.nr * u1, q.nz), outerRim},
              {glm::vec3(q.r * u0, q.z), glm::vec3(q.nr * u0, q.nz), outerRim});
    }
  }
  return triangles;
}

std::vector<RibbonVertex> ribbonStrip(const std::vector<glm::vec2>& points, float width,
                                      const std::vector<bool>& slides, const std::vector<bool>& flies) {
  std::vector<glm::vec2> distinct;
  std::vector<std::size_t> index;
  distinct.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (distinct.empty() || glm::length(points[i] - distinct.back()) > 1e-7f) {
      distinct.push_back(points[i]);
      index.push_back(i);
    }
  }
  std::vector<RibbonVertex> strip;
  if (distinct.size() < 2) return strip;
  strip.reserve(2 * distinct.size());
  const float last = static_cast<float>(std::max<std::size_t>(points.size() - 1, 1));
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    // Central differences inside, one-sided at the ends: the ribbon bends smoothly at each point.
    const glm::vec2 before = distinct[i == 0 ? 0 : i - 1], after = distinct[std::min(i + 1, distinct.size() - 1)];
    const glm::vec2 tangent = glm::normalize(after - before);
    const glm::vec2 side = 0.5f * width * glm::vec2(-tangent.y, tangent.x);
    const float age = 1.0f - static_cast<float>(index[i]) / last;
    const bool flying = index[i] < flies.size() && flies[index[i]];
    const float sliding = flying ? kTraceInTheAir : index[i] < slides.size() && slides[index[i]] ? 1.0f : 0.0f;
    strip.push_back({distinct[i] + side, age, sliding});
    strip.push_back({distinct[i] - side, age, sliding});
  }
  return strip;
}

}  // namespace coinroll::render
