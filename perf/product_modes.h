#pragma once
// Every mode of the exact-rotation product (engine/query/rotated_product.h), made for a
// pose's rotation and read back, each mode's term at the pose in double on the host
// (kernels/pose_query.cl rotated_lines at dtheta = 0):
//   f_k = W_k e^{i phi_k},  phi_k = 2 pi w_k . tau,  tau = t + R c2 - c1,
//   E_k = -Re f_k,  F_k = Re(2 pi i f_k) w_k,  T_k = Re(G_k e^{i phi_k}),
//   G_k = D_k + 2 pi i W_k (R c2 x w_k).
// For the benchmarks that weigh the terms one by one (bench_mode_selection, bench_near_far).
#include <CL/opencl.hpp>
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <complex>
#include <vector>

#include "engine/query/rotated_product.h"
#include "engine/query/translation_lines.h"
#include "engine/spectra/mode_order.h"
#include "snapfit/pose.h"

namespace snapfit::bench {

struct ModeTerm {
  std::complex<double> W, G[3];  // the product and its torque amplitude
  double e = 0;
  Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
};

class ProductModes {
 public:
  ProductModes(const ComputeContext& ctx, const PairSpectra& spectra)
      : spectra_(spectra),
        order_(mode_order(spectra)),
        lines_(build_translation_lines(spectra.dims, order_, false, order_.size())),
        product_(ctx, spectra, lines_),
        box_(ctx.context, CL_MEM_READ_WRITE, product_.box_bytes()),
        queue_(ctx.context, ctx.device.device, 0),
        host_(product_.box_bytes() / sizeof(float)) {
    for (std::size_t i = 0; i < order_.size(); ++i) {
      const std::array<int, 3> k = signed_node(spectra.dims, order_[i]);
      w_.emplace_back(k[0] / spectra.length.x(), k[1] / spectra.length.y(), k[2] / spectra.length.z());
      node_.push_back(box_node(lines_, k[0], k[1], k[2]));
    }
  }

  std::size_t size() const { return order_.size(); }  // every mode, in the engine's order
  const std::vector<Eigen::Vector3d>& frequencies() const { return w_; }

  // Each mode's term at `pose` into terms[0 .. size()).
  void terms(const Pose& pose, std::vector<ModeTerm>& terms) {
    const Eigen::Matrix3d R = pose.rotation.normalized().toRotationMatrix();
    product_.compute(queue_, R, order_.size(), box_);
    queue_.enqueueReadBuffer(box_, CL_TRUE, 0, product_.box_bytes(), host_.data());
    const Eigen::Vector3d tau = pose.translation + R * spectra_.part2.centre - spectra_.part1.centre;
    const Eigen::Vector3d Rc2 = R * spectra_.part2.centre;
    using Cd = std::complex<double>;
    terms.resize(order_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) {
      const float* n = &host_[8 * node_[i]];
      ModeTerm& m = terms[i];
      m.W = Cd(n[0], n[1]);
      const Cd two_pi_i_W = Cd(0, 2 * M_PI) * m.W;
      const Eigen::Vector3d a = Rc2.cross(w_[i]);
      for (int c = 0; c < 3; ++c) m.G[c] = Cd(n[2 + 2 * c], n[3 + 2 * c]) + two_pi_i_W * a[c];
      const double phi = 2 * M_PI * w_[i].dot(tau);
      const Cd e(std::cos(phi), std::sin(phi));
      m.e = -(m.W * e).real();
      m.f = (two_pi_i_W * e).real() * w_[i];
      m.t = Eigen::Vector3d((m.G[0] * e).real(), (m.G[1] * e).real(), (m.G[2] * e).real());
    }
  }

 private:
  const PairSpectra& spectra_;
  std::vector<std::size_t> order_;
  TranslationLines lines_;
  RotatedProduct product_;
  cl::Buffer box_;
  cl::CommandQueue queue_;
  std::vector<float> host_;
  std::vector<Eigen::Vector3d> w_;
  std::vector<std::size_t> node_;
};

}  // namespace snapfit::bench
