#pragma once
// Look-at camera, perspective (vertical field of view) or orthographic (view height).

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>

namespace countershade {

struct Camera {
  glm::dvec3 eye{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
  bool orthographic = false;
  double vertical_fov_deg = 40.0;  // perspective
  double ortho_height = 2.0;       // orthographic: world-space height of the view
  int width = 640, height = 480;
};

// Sets the image size (command-line overrides); one of the two given alone keeps the aspect ratio,
// so the image shows the same framing at another resolution.
void resize(Camera& camera, std::optional<int> width, std::optional<int> height);

struct Ray {
  glm::dvec3 origin, direction;  // direction is unit length
};

// Precomputed basis for generating primary rays.
class CameraRays {
 public:
  explicit CameraRays(const Camera& camera);
  // Ray through film position (x, y) in pixels, (0,0) = top-left corner of the top-left pixel.
  Ray ray(double x, double y) const;
  // Linear eye depth of a world point: distance along the viewing direction.
  double eye_depth(const glm::dvec3& p) const;
  // The world point on the ray through film position (x, y) at linear eye depth `depth` (a depth
  // buffer's value): the point a pixel sees.
  glm::dvec3 point_at_depth(double x, double y, double depth) const;
  // Unit direction from a surface point towards the viewer.
  glm::dvec3 towards_viewer(const glm::dvec3& p) const;
  // Film position (x, y) in pixels of a world point in front of the camera: the inverse of ray().
  glm::dvec2 film_position(const glm::dvec3& p) const;
  // False only when no primary ray can hit the triangle abc: its corners all lie beyond one side
  // of the view (left, right, top, bottom, or behind the eye). True may still be unseen.
  bool may_see(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const;
  // The sides of the view a point lies beyond, one bit each: may_see is false exactly when the
  // corners' bits share one.
  unsigned outside(const glm::dvec3& p) const;
  // The camera's basis: right, up (both on the film) and the viewing direction.
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& up() const { return up_; }
  const glm::dvec3& forward() const { return forward_; }

 private:
  Camera camera_;
  glm::dvec3 forward_, right_, up_;
  double half_height_, half_width_;
};

}  // namespace countershade
