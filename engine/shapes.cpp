#include "engine/shapes.h"

#include <algorithm>
#include <cmath>

namespace talus {

namespace {

class BoxShape final : public Shape {
public:
  BoxShape(const Vec3d& centre, const Vec3d& size, const Mat3d& rot) : c_(centre), h_(0.5 * size), R_(rot) {}
  bool contains(const Vec3d& x) const override {
    const Vec3d l = R_.transpose() * (x - c_);
    return (l.array().abs() <= h_.array()).all();
  }
  void bounds(Vec3d& lo, Vec3d& hi) const override {
    const Vec3d e = R_.cwiseAbs() * h_;
    lo = c_ - e, hi = c_ + e;
  }
  double volume() const override { return 8 * h_.prod(); }
  Vec3d centre() const override { return c_; }
  double distance(const Vec3d& x) const override {
    const Vec3d d = (R_.transpose() * (x - c_)).cwiseAbs() - h_;
    return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
  }
private:
  Vec3d c_, h_;
  Mat3d R_;
};

class SphereShape final : public Shape {
public:
  SphereShape(const Vec3d& c, double r) : c_(c), r_(r) {}
  bool contains(const Vec3d& x) const override { return (x - c_).squaredNorm() <= r_ * r_; }
  void bounds(Vec3d& lo, Vec3d& hi) const override { lo = c_.array() - r_, hi = c_.array() + r_; }
  double volume() const override { return 4.0 / 3.0 * M_PI * r_ * r_ * r_; }
  Vec3d centre() const override { return c_; }
  double distance(const Vec3d& x) const override { return (x - c_).norm() - r_; }
private:
  Vec3d c_;
  double r_;
};

class CylinderShape final : public Shape {
public:
  CylinderShape(const Vec3d& a, const Vec3d& b, double r) : a_(a), b_(b), r_(r) {}
  bool contains(const Vec3d& x) const override {
    const Vec3d ax = b_ - a_;
    const double t = (x - a_).dot(ax) / ax.squaredNorm();
    if (t < 0 || t > 1) return false;
    return (x - a_ - t * ax).squaredNorm() <= r_ * r_;
  }
  void bounds(Vec3d& lo, Vec3d& hi) const override {
    const Vec3d ax = (b_ - a_).normalized();
    const Vec3d e = r_ * (Vec3d::Ones() - ax.cwiseProduct(ax)).cwiseMax(0.0).cwiseSqrt();
    lo = a_.cwiseMin(b_) - e, hi = a_.cwiseMax(b_) + e;
  }
  double volume() const override { return M_PI * r_ * r_ * (b_ - a_).norm(); }
  Vec3d centre() const override { return 0.5 * (a_ + b_); }
  double distance(const Vec3d& x) const override {
    const Vec3d ax = b_ - a_;
    const double L = ax.norm();
    const double t = (x - a_).dot(ax) / L; // along the axis, 0 at start
    const double radial = (x - a_ - t / L * ax).norm() - r_;
    const double axial = std::max(-t, t - L);
    return std::hypot(std::max(radial, 0.0), std::max(axial, 0.0)) + std::min(std::max(radial, axial), 0.0);
  }
private:
  Vec3d a_, b_;
  double r_;
};

} // namespace

std::unique_ptr<Shape> makeBox(const Vec3d& centre, const Vec3d& size, const Mat3d& R) {
  return std::make_unique<BoxShape>(centre, size, R);
}
std::unique_ptr<Shape> makeSphere(const Vec3d& centre, double radius) { return std::make_unique<SphereShape>(centre, radius); }
std::unique_ptr<Shape> makeCylinder(const Vec3d& start, const Vec3d& end, double radius) {
  return std::make_unique<CylinderShape>(start, end, radius);
}

} // namespace talus
