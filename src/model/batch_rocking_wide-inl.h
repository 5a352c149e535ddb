// The wide-vector operations of the batch rocking kernel (src/model/batch_rocking_simd.cpp): one
// concept of their own, kept out of the kernel's file. Included textually inside that file's
// per-target HWY_NAMESPACE by each of Highway's foreach_target passes, hence no include guard; it needs
// `hn` (hwy::HWY_NAMESPACE) and SinCos in scope.
// NOLINT(build/header_guard)
// U Highway vectors handled as one (the dopri5 stages are a chain of dependent sin/cos: one
// vector at a time leaves the core waiting on latency; U independent ones fill it). Every
// operation is the Highway operation on each part: lane results are those of U = 1, bit for bit.
// GCC would otherwise call the stage lambda out of line, passing U vectors through memory.
#define HWY_INLINE_LAMBDA __attribute__((always_inline))
namespace w {
using D = hn::ScalableTag<double>;
using HV = hn::Vec<D>;
using HM = hn::Mask<D>;
template <std::size_t U>
struct Wide {
  HV v[U];
};
template <std::size_t U>
struct WMask {
  HM m[U];
};
template <std::size_t U>
struct Tag {
  D d;
  std::size_t lanes() const { return U * hn::Lanes(d); }
};
#define RM_W_UNARY(Name)                                          \
  template <std::size_t U>                                        \
  HWY_INLINE Wide<U> Name(Wide<U> a) {                            \
    Wide<U> r;                                                    \
    for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Name(a.v[u]); \
    return r;                                                     \
  }
// A two-operand Highway operation lifted over the U registers: Out r.of[u] = hn::Name(a.in[u], b.in[u]).
#define RM_W_LIFT2(Name, In, in, Out, of)                                    \
  template <std::size_t U>                                                   \
  HWY_INLINE Out<U> Name(In<U> a, In<U> b) {                                 \
    Out<U> r;                                                                \
    for (std::size_t u = 0; u < U; ++u) r.of[u] = hn::Name(a.in[u], b.in[u]); \
    return r;                                                                \
  }
#define RM_W_BINARY(Name) RM_W_LIFT2(Name, Wide, v, Wide, v)
#define RM_W_COMPARE(Name) RM_W_LIFT2(Name, Wide, v, WMask, m)
#define RM_W_MASK2(Name) RM_W_LIFT2(Name, WMask, m, WMask, m)
RM_W_UNARY(Abs)
RM_W_UNARY(Neg)
RM_W_UNARY(Sqrt)
RM_W_BINARY(Add)
RM_W_BINARY(Sub)
RM_W_BINARY(Mul)
RM_W_BINARY(Div)
RM_W_BINARY(Min)
RM_W_BINARY(Max)
RM_W_COMPARE(Eq)
RM_W_COMPARE(Ne)
RM_W_COMPARE(Lt)
RM_W_COMPARE(Le)
RM_W_COMPARE(Gt)
RM_W_COMPARE(Ge)
RM_W_MASK2(And)
RM_W_MASK2(Or)
RM_W_MASK2(AndNot)
#undef RM_W_UNARY
#undef RM_W_BINARY
#undef RM_W_COMPARE
#undef RM_W_MASK2
#undef RM_W_LIFT2
template <std::size_t U>
HWY_INLINE WMask<U> Not(WMask<U> a) {
  WMask<U> r;
  for (std::size_t u = 0; u < U; ++u) r.m[u] = hn::Not(a.m[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE WMask<U> IsFinite(Wide<U> a) {
  WMask<U> r;
  for (std::size_t u = 0; u < U; ++u) r.m[u] = hn::IsFinite(a.v[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> IfThenElse(WMask<U> m, Wide<U> a, Wide<U> b) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::IfThenElse(m.m[u], a.v[u], b.v[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> IfThenElseZero(WMask<U> m, Wide<U> a) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::IfThenElseZero(m.m[u], a.v[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE bool AllFalse(Tag<U> t, WMask<U> m) {
  bool all = true;
  for (std::size_t u = 0; u < U; ++u) all = all && hn::AllFalse(t.d, m.m[u]);
  return all;
}
template <std::size_t U>
HWY_INLINE Wide<U> Set(Tag<U> t, double x) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Set(t.d, x);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> Zero(Tag<U> t) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Zero(t.d);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> LoadU(Tag<U> t, const double* p) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::LoadU(t.d, p + u * hn::Lanes(t.d));
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> Load(Tag<U> t, const double* p) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Load(t.d, p + u * hn::Lanes(t.d));
  return r;
}
template <std::size_t U>
HWY_INLINE void StoreU(Wide<U> a, Tag<U> t, double* p) {
  for (std::size_t u = 0; u < U; ++u) hn::StoreU(a.v[u], t.d, p + u * hn::Lanes(t.d));
}
template <std::size_t U>
HWY_INLINE void Store(Wide<U> a, Tag<U> t, double* p) {
  for (std::size_t u = 0; u < U; ++u) hn::Store(a.v[u], t.d, p + u * hn::Lanes(t.d));
}
template <std::size_t U>
HWY_INLINE Wide<U> Sin(Tag<U> t, Wide<U> a) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Sin(t.d, a.v[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> Cos(Tag<U> t, Wide<U> a) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Cos(t.d, a.v[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> Exp(Tag<U> t, Wide<U> a) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Exp(t.d, a.v[u]);
  return r;
}
template <std::size_t U>
HWY_INLINE Wide<U> Log(Tag<U> t, Wide<U> a) {
  Wide<U> r;
  for (std::size_t u = 0; u < U; ++u) r.v[u] = hn::Log(t.d, a.v[u]);
  return r;
}
template <bool kExact, std::size_t U>
HWY_INLINE void SinCos(Tag<U> t, Wide<U> phi, Wide<U>& s, Wide<U>& c) {
  for (std::size_t u = 0; u < U; ++u) batch_detail::HWY_NAMESPACE::SinCos<kExact>(t.d, phi.v[u], s.v[u], c.v[u]);
}
}  // namespace w
