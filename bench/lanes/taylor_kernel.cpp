// One heavy-top Taylor expansion (taylor_fixed<15>, the order of rtol 1e-12) per member, three
// ways: on double (as a sweep's scalar kernels run it), on one xsimd batch (4 doubles with AVX2,
// as --lanes 4 runs it and --lanes 8 twice a call; 8 with AVX-512, as a `taylor` scene's --lanes 8
// runs it there), and on two batches interleaved in one pass (if the batch expansion waited on
// its chain of orders, two independent chains would hide that wait). ns per member (per lane), the
// median of 15 timings. Built by bench/lanes/taylor_kernel.sh with the generated header as
// UNIT_HEADER, namespace UNIT.
#include <xsimd/xsimd.hpp>

#include <cmath>

using batch = xsimd::batch<double>;

namespace two {
// Two batches as one scalar type for the generated templates (+ - * /, sin, cos by ADL)
struct batches {
    batch a, b;
    batches() = default;
    batches(double x) : a(x), b(x) {}
    batches(batch x, batch y) : a(x), b(y) {}
};
inline batches operator+(const batches& x, const batches& y) {
    return {x.a + y.a, x.b + y.b};
}
inline batches operator-(const batches& x, const batches& y) {
    return {x.a - y.a, x.b - y.b};
}
inline batches operator*(const batches& x, const batches& y) {
    return {x.a * y.a, x.b * y.b};
}
inline batches operator/(const batches& x, const batches& y) {
    return {x.a / y.a, x.b / y.b};
}
inline batches operator-(const batches& x) {
    return {-x.a, -x.b};
}
inline batches& operator+=(batches& x, const batches& y) {
    return x = x + y;
}
inline batches& operator-=(batches& x, const batches& y) {
    return x = x - y;
}
inline batches& operator*=(batches& x, const batches& y) {
    return x = x * y;
}
inline batches sin(const batches& x) {
    return {xsimd::sin(x.a), xsimd::sin(x.b)};
}
inline batches cos(const batches& x) {
    return {xsimd::cos(x.a), xsimd::cos(x.b)};
}
} // namespace two

#include UNIT_HEADER

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

namespace m = rotgen::models::UNIT;

namespace {

constexpr int order = 15, members = 24000;

// ns per member of taylor_fixed<order> on T, which carries `lanes` members
template <class T> double ns_per_member(int lanes) {
    const int stride = order + 1;
    std::vector<T> c(m::taylor_series * stride, T(0.0));
    const m::params<T> p;
    std::vector<double> ns;
    for (int round = 0; round < 15; ++round) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < members / lanes; ++i) {
            const double y0[6] = {0, 0.5 + 1e-9 * i, 0, 0, 0, 30}; // the sweep's heavy top
            for (int s = 0; s < 6; ++s)
                c[s * stride] = T(y0[s]);
            m::taylor_fixed<order>(T(0.0), c.data(), p);
            asm volatile("" : : "r"(c.data()) : "memory");
        }
        const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
        ns.push_back(dt.count() * 1e9 / members);
    }
    std::sort(ns.begin(), ns.end());
    return ns[ns.size() / 2];
}

} // namespace

int main() {
    const int w = static_cast<int>(batch::size); // 4 with AVX2, 8 with AVX-512
    const double scalar = ns_per_member<double>(1), one = ns_per_member<batch>(w),
                 pair = ns_per_member<two::batches>(2 * w);
    std::printf("%.0f %.0f %.0f\n", scalar, one, pair);
}
