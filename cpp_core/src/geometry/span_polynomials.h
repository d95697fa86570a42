// Span-by-span power-form evaluation of a B-spline / Bezier surface: the
// metrics' Newton projections evaluate D2 ~100 times a panel, and OCCT's
// GeomAdaptor_Surface takes 100-300 ns a call. Each knot span becomes its
// Taylor polynomial about the span's middle (centred, so Horner stays well
// conditioned), built on first use and kept in a small direct-mapped table
// (16 x 16 neighbouring spans stay cached together). Rational surfaces keep
// the homogeneous (wx, wy, wz, w) polynomial and divide by the quotient rule.
//
// Spans as OCCT picks them: a parameter on an interior knot (or an ulp below
// it) belongs to the span above it, the last knot to the last span (so at a
// C1 knot the second derivatives are the upper span's, as
// Geom_BSplineSurface::D2 gives them); the end spans extend beyond the
// range. Not thread-safe: one per thread (one per FastEvaluation scope).
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <array>
#include <memory>
#include <vector>

namespace tessella {

class SpanPolynomials {
 public:
  // Null for what it does not handle: periodic B-splines, degree > kMaxDegree,
  // any other kind of surface (the caller keeps OCCT's evaluation then).
  static std::unique_ptr<SpanPolynomials> create(const Handle(Geom_Surface) & surface);
  static constexpr int kMaxDegree = 9;

  SpanPolynomials(const SpanPolynomials&) = delete;
  SpanPolynomials& operator=(const SpanPolynomials&) = delete;

  // The point, then its first and second derivatives (3 doubles each).
  void d0(double u, double v, double p[3]);
  void d1(double u, double v, double p[3], double du[3], double dv[3]);
  void d2(double u, double v, double p[3], double du[3], double dv[3], double duu[3], double dvv[3],
          double duv[3]);

 private:
  // S, Su, Sv, Suu, Svv, Suv of the (homogeneous) polynomial, in that order.
  using Derivatives = double[6][4];
  // Horner evaluation of one span's coefficients up to derivative order 0..2.
  using Kernel = void (*)(const double* c, int p, int q, double s, double t, Derivatives& out);

  explicit SpanPolynomials(const Handle(Geom_BSplineSurface) & bs);

  // One parameter direction: its spans and the one found last.
  struct Axis {
    std::vector<double> knots;   // distinct knots of the parameter range
    std::vector<double> lo, hi;  // where span i surely holds t (see .cpp)
    double last = 0;             // the surface's last knot (OCCT's locating tolerance)
    int current = 0;
    int find(double t) {
      const auto i = static_cast<std::size_t>(current);
      if (t >= lo[i] && t < hi[i]) return current;
      return current = step(t);
    }
    int step(double t) const;  // a neighbour of the current span, else a search
    void init(const Handle(Geom_BSplineSurface) & bs, bool u);
    // The derivatives 0..degree of the span's non-zero basis functions at its
    // middle (row i: the i-th derivatives; (degree + 1)^2 doubles) and, in
    // `first_pole`, the 1-based index of its first pole. Evaluated on first
    // use and kept: every span of a row shares its u basis (OCCT's
    // EvalBsplineBasis was a third of a span's fill).
    const double* basis_of(int span, int& first_pole);

    int degree = 0;
    const TColStd_Array1OfReal* sequence = nullptr;  // the flat knots (the surface owns them)
    std::vector<double> basis;
    std::vector<int> first;  // per span: its first pole, 0 until evaluated
  };
  struct Slot {
    int iu = -1, iv = -1;          // the span held (indices into the distinct knots)
    double um = 0, vm = 0;         // the expansion point
    double origin[3] = {0, 0, 0};  // subtracted from the span's poles (accuracy)
  };
  static constexpr unsigned kSide = 16;

  // The slot of the span holding (u, v), its coefficients built if missing.
  std::size_t slot(double u, double v) {
    const int iu = u_.find(u), iv = v_.find(v);
    const std::size_t k =
        (static_cast<unsigned>(iu) % kSide) * kSide + static_cast<unsigned>(iv) % kSide;
    if (slots_[k].iu != iu || slots_[k].iv != iv) fill(k, iu, iv);
    return k;
  }
  void fill(std::size_t slot, int iu, int iv);
  // fill's power-form sums, unrolled for the common degrees.
  using Expand = void (*)(int p, int q, const double* bu, const double* bv, const double* h,
                          double* c);
  Expand expand_ = nullptr;
  // The polynomial's derivatives at (u, v); returns the span's origin.
  const double* eval(int order, double u, double v, Derivatives& out);
  // The point and derivatives from the homogeneous ones.
  void finish(int order, Derivatives& h, const double origin[3], double* out[6]) const;

  Handle(Geom_BSplineSurface) surface_;  // owns the poles, weights and knots read
  int p_ = 0, q_ = 0, dim_ = 3;          // degrees in u and v; 4 when rational
  int stride_ = 0;                       // coefficients a span: (p+1)(q+1)dim
  std::array<Kernel, 3> kernels_{};      // by derivative order
  Axis u_, v_;
  std::array<Slot, kSide * kSide> slots_;
  std::vector<double> coeffs_;  // stride_ per slot: c[i][j][d] = d^(i+j)S/du^i dv^j / (i! j!)
};

}  // namespace tessella
