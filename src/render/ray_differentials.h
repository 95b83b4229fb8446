#pragma once
// The footprint of a pixel on a surface, for choosing a texture's mip level (render/texture.h).
// The rays through the film one pixel to the right and one pixel down meet the hit's tangent
// plane; the offsets from the hit, carried into UV through the triangle's parametrisation, are
// the UV derivatives per pixel (ray differentials).

#include "render/camera.h"
#include "render/shading.h"

namespace countershade {

// Sets sp.duv_dx and sp.duv_dy from the neighbouring camera rays. Leaves them 0 where the mesh has
// no UVs or a neighbouring ray runs parallel to the tangent plane.
void set_uv_differentials(const Scene& scene, const Ray& right, const Ray& down, SurfacePoint& sp);

}  // namespace countershade
