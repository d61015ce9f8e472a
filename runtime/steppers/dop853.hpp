/// \file
/// rotgen runtime — Dormand–Prince 8(5,3) (Hairer's DOP853) with 7th-order dense output.
///
/// Method (Hairer, Nørsett & Wanner I, §II.10, and the code DOP853): 12 stages for the 8th-order
/// solution y1 = y0 + h Σ b_i k_i; f(t + h, y1) = k13 is computed after acceptance and is the next
/// step's k1 (FSAL), so 12 evaluations of f per accepted step.
/// Error estimate (DOP853's "stretched" 5th/3rd-order combination):
///   e5_i = Σ er_j k_j,   e3_i = Σ b_j k_j − (bhh1 k1 + bhh2 k9 + bhh3 k12),
///   sk_i = atol + rtol·max(|y0_i|, |y1_i|),   E5 = Σ (e5_i/sk_i)²,  E3 = Σ (e3_i/sk_i)²,
///   err  = |h| · E5 / sqrt(n · (E5 + 0.01·E3)),
/// which behaves like O(h^8): controller exponent 1/8 (q = 8). Hairer's defaults: beta = 0
/// (I controller), facmin = 0.333, facmax = 6.
/// Dense output (DOP853's CONTD8): three more stages k14, k15, k16 (computed only in steps that
/// hold samples) give, with θ = (t − t_n)/h and θ1 = 1 − θ,
///   y(θ) = r1 + θ(r2 + θ1(r3 + θ(r4 + θ1(r5 + θ(r6 + θ1(r7 + θ r8))))))
///   r1 = y0, r2 = y1 − y0, r3 = h k1 − r2, r4 = r2 − h k13 − r3, r5..r8 = h Σ d_{4..7,j} k_j,
/// a continuous extension of order 7 (local error O(h^8)).
/// The coefficients are Hairer's published constants (30 digits); tests check the consistency
/// conditions Σ_j a_ij = c_i, Σ b = 1, Σ er = 0 and the orders 8 and 7 numerically.
/// Stepper concept (stepper.hpp): order 8, error estimate, own dense output of order 7, no
/// Jacobian.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "../combine.hpp"
#include "../derivatives.hpp"
#include "../lanes.hpp"
#include "../step_control.hpp"
#include "../stepper.hpp"

namespace rotgen {

/// The coefficients of DOP853 (Hairer's published constants, 30 digits, in long double).
struct dop853_tableau {
    /// \name Coefficients
    ///@{

    /// The nodes c_i, the weights b_i, bhh_i and er_i of the error estimate, the stages' a_ij and
    /// the dense output's d_ij (see the file's comment).
    static constexpr long double c2 = 0.526001519587677318785587544488e-01L;
    static constexpr long double c3 = 0.789002279381515978178381316732e-01L;
    static constexpr long double c4 = 0.118350341907227396726757197510e+00L;
    static constexpr long double c5 = 0.281649658092772603273242802490e+00L;
    static constexpr long double c6 = 0.333333333333333333333333333333e+00L;
    static constexpr long double c7 = 0.25e+00L;
    static constexpr long double c8 = 0.307692307692307692307692307692e+00L;
    static constexpr long double c9 = 0.651282051282051282051282051282e+00L;
    static constexpr long double c10 = 0.6e+00L;
    static constexpr long double c11 = 0.857142857142857142857142857142e+00L;
    static constexpr long double c14 = 0.1e+00L, c15 = 0.2e+00L,
                                 c16 = 0.777777777777777777777777777778e+00L;

    static constexpr long double b1 = 5.42937341165687622380535766363e-2L;
    static constexpr long double b6 = 4.45031289275240888144113950566e0L;
    static constexpr long double b7 = 1.89151789931450038304281599044e0L;
    static constexpr long double b8 = -5.8012039600105847814672114227e0L;
    static constexpr long double b9 = 3.1116436695781989440891606237e-1L;
    static constexpr long double b10 = -1.52160949662516078556178806805e-1L;
    static constexpr long double b11 = 2.01365400804030348374776537501e-1L;
    static constexpr long double b12 = 4.47106157277725905176885569043e-2L;

    static constexpr long double bhh1 = 0.244094488188976377952755905512e+00L;
    static constexpr long double bhh2 = 0.733846688281611857341361741547e+00L;
    static constexpr long double bhh3 = 0.220588235294117647058823529412e-01L;

    static constexpr long double er1 = 0.1312004499419488073250102996e-01L;
    static constexpr long double er6 = -0.1225156446376204440720569753e+01L;
    static constexpr long double er7 = -0.4957589496572501915214079952e+00L;
    static constexpr long double er8 = 0.1664377182454986536961530415e+01L;
    static constexpr long double er9 = -0.3503288487499736816886487290e+00L;
    static constexpr long double er10 = 0.3341791187130174790297318841e+00L;
    static constexpr long double er11 = 0.8192320648511571246570742613e-01L;
    static constexpr long double er12 = -0.2235530786388629525884427845e-01L;

    static constexpr long double a21 = 5.26001519587677318785587544488e-2L;
    static constexpr long double a31 = 1.97250569845378994544595329183e-2L;
    static constexpr long double a32 = 5.91751709536136983633785987549e-2L;
    static constexpr long double a41 = 2.95875854768068491816892993775e-2L;
    static constexpr long double a43 = 8.87627564304205475450678981324e-2L;
    static constexpr long double a51 = 2.41365134159266685502369798665e-1L;
    static constexpr long double a53 = -8.84549479328286085344864962717e-1L;
    static constexpr long double a54 = 9.24834003261792003115737966543e-1L;
    static constexpr long double a61 = 3.7037037037037037037037037037e-2L;
    static constexpr long double a64 = 1.70828608729473871279604482173e-1L;
    static constexpr long double a65 = 1.25467687566822425016691814123e-1L;
    static constexpr long double a71 = 3.7109375e-2L;
    static constexpr long double a74 = 1.70252211019544039314978060272e-1L;
    static constexpr long double a75 = 6.02165389804559606850219397283e-2L;
    static constexpr long double a76 = -1.7578125e-2L;
    static constexpr long double a81 = 3.70920001185047927108779319836e-2L;
    static constexpr long double a84 = 1.70383925712239993810214054705e-1L;
    static constexpr long double a85 = 1.07262030446373284651809199168e-1L;
    static constexpr long double a86 = -1.53194377486244017527936158236e-2L;
    static constexpr long double a87 = 8.27378916381402288758473766002e-3L;
    static constexpr long double a91 = 6.24110958716075717114429577812e-1L;
    static constexpr long double a94 = -3.36089262944694129406857109825e0L;
    static constexpr long double a95 = -8.68219346841726006818189891453e-1L;
    static constexpr long double a96 = 2.75920996994467083049415600797e1L;
    static constexpr long double a97 = 2.01540675504778934086186788979e1L;
    static constexpr long double a98 = -4.34898841810699588477366255144e1L;
    static constexpr long double a101 = 4.77662536438264365890433908527e-1L;
    static constexpr long double a104 = -2.48811461997166764192642586468e0L;
    static constexpr long double a105 = -5.90290826836842996371446475743e-1L;
    static constexpr long double a106 = 2.12300514481811942347288949897e1L;
    static constexpr long double a107 = 1.52792336328824235832596922938e1L;
    static constexpr long double a108 = -3.32882109689848629194453265587e1L;
    static constexpr long double a109 = -2.03312017085086261358222928593e-2L;
    static constexpr long double a111 = -9.3714243008598732571704021658e-1L;
    static constexpr long double a114 = 5.18637242884406370830023853209e0L;
    static constexpr long double a115 = 1.09143734899672957818500254654e0L;
    static constexpr long double a116 = -8.14978701074692612513997267357e0L;
    static constexpr long double a117 = -1.85200656599969598641566180701e1L;
    static constexpr long double a118 = 2.27394870993505042818970056734e1L;
    static constexpr long double a119 = 2.49360555267965238987089396762e0L;
    static constexpr long double a1110 = -3.0467644718982195003823669022e0L;
    static constexpr long double a121 = 2.27331014751653820792359768449e0L;
    static constexpr long double a124 = -1.05344954667372501984066689879e1L;
    static constexpr long double a125 = -2.00087205822486249909675718444e0L;
    static constexpr long double a126 = -1.79589318631187989172765950534e1L;
    static constexpr long double a127 = 2.79488845294199600508499808837e1L;
    static constexpr long double a128 = -2.85899827713502369474065508674e0L;
    static constexpr long double a129 = -8.87285693353062954433549289258e0L;
    static constexpr long double a1210 = 1.23605671757943030647266201528e1L;
    static constexpr long double a1211 = 6.43392746015763530355970484046e-1L;

    static constexpr long double a141 = 5.61675022830479523392909219681e-2L;
    static constexpr long double a147 = 2.53500210216624811088794765333e-1L;
    static constexpr long double a148 = -2.46239037470802489917441475441e-1L;
    static constexpr long double a149 = -1.24191423263816360469010140626e-1L;
    static constexpr long double a1410 = 1.5329179827876569731206322685e-1L;
    static constexpr long double a1411 = 8.20105229563468988491666602057e-3L;
    static constexpr long double a1412 = 7.56789766054569976138603589584e-3L;
    static constexpr long double a1413 = -8.298e-3L;
    static constexpr long double a151 = 3.18346481635021405060768473261e-2L;
    static constexpr long double a156 = 2.83009096723667755288322961402e-2L;
    static constexpr long double a157 = 5.35419883074385676223797384372e-2L;
    static constexpr long double a158 = -5.49237485713909884646569340306e-2L;
    static constexpr long double a1511 = -1.08347328697249322858509316994e-4L;
    static constexpr long double a1512 = 3.82571090835658412954920192323e-4L;
    static constexpr long double a1513 = -3.40465008687404560802977114492e-4L;
    static constexpr long double a1514 = 1.41312443674632500278074618366e-1L;
    static constexpr long double a161 = -4.28896301583791923408573538692e-1L;
    static constexpr long double a166 = -4.69762141536116384314449447206e0L;
    static constexpr long double a167 = 7.68342119606259904184240953878e0L;
    static constexpr long double a168 = 4.06898981839711007970213554331e0L;
    static constexpr long double a169 = 3.56727187455281109270669543021e-1L;
    static constexpr long double a1613 = -1.39902416515901462129418009734e-3L;
    static constexpr long double a1614 = 2.9475147891527723389556272149e0L;
    static constexpr long double a1615 = -9.15095847217987001081870187138e0L;

    static constexpr long double d41 = -0.84289382761090128651353491142e+01L;
    static constexpr long double d46 = 0.56671495351937776962531783590e+00L;
    static constexpr long double d47 = -0.30689499459498916912797304727e+01L;
    static constexpr long double d48 = 0.23846676565120698287728149680e+01L;
    static constexpr long double d49 = 0.21170345824450282767155149946e+01L;
    static constexpr long double d410 = -0.87139158377797299206789907490e+00L;
    static constexpr long double d411 = 0.22404374302607882758541771650e+01L;
    static constexpr long double d412 = 0.63157877876946881815570249290e+00L;
    static constexpr long double d413 = -0.88990336451333310820698117400e-01L;
    static constexpr long double d414 = 0.18148505520854727256656404962e+02L;
    static constexpr long double d415 = -0.91946323924783554000451984436e+01L;
    static constexpr long double d416 = -0.44360363875948939664310572000e+01L;
    static constexpr long double d51 = 0.10427508642579134603413151009e+02L;
    static constexpr long double d56 = 0.24228349177525818288430175319e+03L;
    static constexpr long double d57 = 0.16520045171727028198505394887e+03L;
    static constexpr long double d58 = -0.37454675472269020279518312152e+03L;
    static constexpr long double d59 = -0.22113666853125306036270938578e+02L;
    static constexpr long double d510 = 0.77334326684722638389603898808e+01L;
    static constexpr long double d511 = -0.30674084731089398182061213626e+02L;
    static constexpr long double d512 = -0.93321305264302278729567221706e+01L;
    static constexpr long double d513 = 0.15697238121770843886131091075e+02L;
    static constexpr long double d514 = -0.31139403219565177677282850411e+02L;
    static constexpr long double d515 = -0.93529243588444783865713862664e+01L;
    static constexpr long double d516 = 0.35816841486394083752465898540e+02L;
    static constexpr long double d61 = 0.19985053242002433820987653617e+02L;
    static constexpr long double d66 = -0.38703730874935176555105901742e+03L;
    static constexpr long double d67 = -0.18917813819516756882830838328e+03L;
    static constexpr long double d68 = 0.52780815920542364900561016686e+03L;
    static constexpr long double d69 = -0.11573902539959630126141871134e+02L;
    static constexpr long double d610 = 0.68812326946963000169666922661e+01L;
    static constexpr long double d611 = -0.10006050966910838403183860980e+01L;
    static constexpr long double d612 = 0.77771377980534432092869265740e+00L;
    static constexpr long double d613 = -0.27782057523535084065932004339e+01L;
    static constexpr long double d614 = -0.60196695231264120758267380846e+02L;
    static constexpr long double d615 = 0.84320405506677161018159903784e+02L;
    static constexpr long double d616 = 0.11992291136182789328035130030e+02L;
    static constexpr long double d71 = -0.25693933462703749003312586129e+02L;
    static constexpr long double d76 = -0.15418974869023643374053993627e+03L;
    static constexpr long double d77 = -0.23152937917604549567536039109e+03L;
    static constexpr long double d78 = 0.35763911791061412378285349910e+03L;
    static constexpr long double d79 = 0.93405324183624310003907691704e+02L;
    static constexpr long double d710 = -0.37458323136451633156875139351e+02L;
    static constexpr long double d711 = 0.10409964950896230045147246184e+03L;
    static constexpr long double d712 = 0.29840293426660503123344363579e+02L;
    static constexpr long double d713 = -0.43533456590011143754432175058e+02L;
    static constexpr long double d714 = 0.96324553959188282948394950600e+02L;
    static constexpr long double d715 = -0.39177261675615439165231486172e+02L;
    static constexpr long double d716 = -0.14972683625798562581422125276e+03L;
    ///@}
};

template <class T, class S> class dop853_stepper;

/// Options: adaptive_options with DOP853's defaults (safety 0.9, facmin 0.333, facmax 6, beta 0).
template <class T> struct dop853 : adaptive_options<T> {
    using scalar = T; ///< the floating-point type of the run
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Error-controlled: the options are adaptive_options and the stepper has an error estimate.
    static constexpr bool adaptive = true;
    /// The stepper for a system of type S.
    template <class S> using stepper = dop853_stepper<T, S>;

    /// calibrate()'s values for scenes (bench/proportionality: rtol means the error at the samples)
    static constexpr double calibrated_scale = 0.25;
    static constexpr double calibrated_power = -1.0 / 8; ///< see calibrated_scale

    dop853() {
        this->facmin = T(0.333);
        this->facmax = T(6);
        this->beta = T(0);
    }
    /// The defaults with the tolerances rtol, atol.
    dop853(T rtol, T atol) : dop853() {
        this->rtol = rtol;
        this->atol = atol;
    }
    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "dop853"; }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const { return detail::check_adaptive_options<T>(*this); }
};

/// DOP853's working storage for one system type S (the stepper concept of stepper.hpp; the method
/// in the file's comment).
template <class T, class S> class dop853_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    /// The work vector of the stage arithmetic (combine.hpp).
    using work = detail::work_vector<T, S>;
    /// The method's coefficients.
    using tab = dop853_tableau;

    /// What attempt() returns.
    using outcome = step_outcome<T>;

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = 8;
    /// Holds its estimate per unit step under a layout with a span (step_control.hpp).
    static constexpr bool per_unit_step = true;
    /// attempt() returns a weighted error norm (step accepted when <= 1).
    static constexpr bool error_estimate = true;
    /// Samples inside a step come from the stepper's own interpolant, dense().
    static constexpr dense_kind dense_output = dense_kind::continuous_extension;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = 7;
    /// Never evaluates ∂f/∂y.
    static constexpr bool uses_jacobian = false;

    /// Storage for n state components, with the tolerances of m (and a fixed step when
    /// m.fixed_step > 0: no error control).
    dop853_stepper(const dop853<T>& m, std::size_t n)
        : m_atol(m.atol * factor(m)), m_rtol(m.rtol * factor(m)), m_layout(m.layout),
          m_fixed(m.fixed_step > T(0)) {
        const auto zero = detail::make_work_vector<work>(n);
        m_y0 = m_y1 = m_k1 = m_y0_scratch = m_arg_scratch = m_bk = m_inv = zero;
        m_k.fill(zero);
        m_r.fill(zero);
    }

    /// f(t0, y0), after start() (for the initial step selection).
    const work& f_start() const { return m_k1; }
    /// The state at t + h of the last attempt().
    const work& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        work y = m_y0;
        detail::assign(y, y0);
        detail::eval_rhs(sys, t0, y, m_k1, stats);
        return detail::all_finite(m_k1);
    }

    /// One step of size h from (t, y): stages 2..12, y1 and the error estimate (see combine.hpp
    /// for where the stages are kept).
    ROTGEN_ALWAYS_INLINE outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats,
                                         bool need_dense) {
        m_t = t;
        m_h = h;
        if constexpr (static_state_size<S>() > 0) {
            if (need_dense) return attempt_keeping_stages(sys, t, y, h, stats);
            stages local;
            return steps(sys, t, y, h, stats, local);
        } else {
            return steps(sys, t, y, h, stats, m_k);
        }
    }

    /// After an accepted step: k13 = f(t + h, y1), the next step's k1 (FSAL), and the dense output
    /// if the step holds samples.
    ROTGEN_ALWAYS_INLINE bool accept(const S& sys, step_stats& stats, bool need_dense) {
        if (need_dense) return accept_dense(sys, stats);
        detail::eval_rhs(sys, m_t + m_h, m_y1, m_k1, stats);
        return detail::all_finite(m_k1);
    }

    /// y(θ) = r1 + θ(r2 + θ1(r3 + θ(r4 + θ1(r5 + θ(r6 + θ1(r7 + θ r8)))))), θ1 = 1 − θ
    void dense(T s, vector& out) const {
        const T s1 = T(1) - s;
        for (std::size_t i = 0; i < detail::size_of(m_y0); ++i)
            out[static_cast<Eigen::Index>(i)] =
                m_y0[i] +
                s * (r(2)[i] +
                     s1 * (r(3)[i] +
                           s * (r(4)[i] +
                                s1 * (r(5)[i] + s * (r(6)[i] + s1 * (r(7)[i] + s * r(8)[i]))))));
    }

  private:
    using stages = std::array<work, 16>; ///< k1..k16

    /// Stages 2..12, y1 and the error estimate, with the stages in k (k[0] receives k1).
    ROTGEN_ALWAYS_INLINE outcome steps(const S& sys, T t, const vector& y, T h, step_stats& stats,
                                       stages& k) {
        if constexpr (static_state_size<S>() > 0) {
            work y0 = m_k1, arg = m_k1; // locals: kept in registers
            return stages_from(sys, t, y, h, stats, k, y0, arg);
        } else { // the stepper's own: no allocation per step
            return stages_from(sys, t, y, h, stats, k, m_y0_scratch, m_arg_scratch);
        }
    }

    /// The same, with y0 and the stage argument in `y0` and `arg`.
    ROTGEN_ALWAYS_INLINE outcome stages_from(const S& sys, T t, const vector& y, T h,
                                             step_stats& stats, stages& k, work& y0, work& arg) {
        using detail::stage;
        detail::assign(y0, y);
        k[0] = m_k1;
        auto f = [&](int i, long double c) {
            detail::eval_rhs(sys, t + T(c) * h, arg, k[static_cast<std::size_t>(i - 1)], stats);
        };
        auto a = [&](long double coefficient, int j) {
            return detail::make_term<T>(coefficient, k[static_cast<std::size_t>(j - 1)]);
        };
        stage(arg, y0, h, a(tab::a21, 1));
        f(2, tab::c2);
        stage(arg, y0, h, a(tab::a32, 2), a(tab::a31, 1));
        f(3, tab::c3);
        stage(arg, y0, h, a(tab::a43, 3), a(tab::a41, 1));
        f(4, tab::c4);
        stage(arg, y0, h, a(tab::a54, 4), a(tab::a51, 1), a(tab::a53, 3));
        f(5, tab::c5);
        stage(arg, y0, h, a(tab::a65, 5), a(tab::a61, 1), a(tab::a64, 4));
        f(6, tab::c6);
        stage(arg, y0, h, a(tab::a76, 6), a(tab::a71, 1), a(tab::a74, 4), a(tab::a75, 5));
        f(7, tab::c7);
        stage(arg, y0, h, a(tab::a87, 7), a(tab::a81, 1), a(tab::a84, 4), a(tab::a85, 5),
              a(tab::a86, 6));
        f(8, tab::c8);
        stage(arg, y0, h, a(tab::a98, 8), a(tab::a91, 1), a(tab::a94, 4), a(tab::a95, 5),
              a(tab::a96, 6), a(tab::a97, 7));
        f(9, tab::c9);
        stage(arg, y0, h, a(tab::a109, 9), a(tab::a101, 1), a(tab::a104, 4), a(tab::a105, 5),
              a(tab::a106, 6), a(tab::a107, 7), a(tab::a108, 8));
        f(10, tab::c10);
        stage(arg, y0, h, a(tab::a1110, 10), a(tab::a111, 1), a(tab::a114, 4), a(tab::a115, 5),
              a(tab::a116, 6), a(tab::a117, 7), a(tab::a118, 8), a(tab::a119, 9));
        f(11, tab::c11);
        stage(arg, y0, h, a(tab::a1211, 11), a(tab::a121, 1), a(tab::a124, 4), a(tab::a125, 5),
              a(tab::a126, 6), a(tab::a127, 7), a(tab::a128, 8), a(tab::a129, 9),
              a(tab::a1210, 10));
        f(12, 1.0L);
        return solution_and_error(sys, y0, h, k);
    }

    /// y1 = y0 + h Σ b_i k_i (8th order) and the error estimate:
    ///   e3 = Σ b k − (bhh1 k1 + bhh2 k9 + bhh3 k12),  e5 = Σ er_j k_j
    /// (for a lane system: the largest of the lanes' norms, lanes.hpp)
    ROTGEN_ALWAYS_INLINE outcome solution_and_error(const S& sys, const work& y0, T h,
                                                    const stages& k) {
        using std::abs;
        using std::max;
        using std::sqrt;
        const std::size_t n = detail::size_of(y0);
        m_y0 = y0;
        const auto b_k = [&](std::size_t i) { // Σ b_j k_j, component i
            return T(tab::b1) * k[0][i] + T(tab::b6) * k[5][i] + T(tab::b7) * k[6][i] +
                   T(tab::b8) * k[7][i] + T(tab::b9) * k[8][i] + T(tab::b10) * k[9][i] +
                   T(tab::b11) * k[10][i] + T(tab::b12) * k[11][i];
        };
        if (m_fixed) { // no error control: y1 only
            for (std::size_t i = 0; i < n; ++i)
                m_y1[i] = y0[i] + h * b_k(i);
            return {detail::all_finite(m_y1) ? status::ok : status::non_finite, T(0)};
        }
        for (std::size_t i = 0; i < n; ++i) {
            m_bk[i] = b_k(i);
            m_y1[i] = y0[i] + h * m_bk[i];
        }
        detail::inverse_scales(m_layout, y0, m_y1, m_atol, m_rtol, detail::lanes_of(sys), m_inv);
        detail::lane_error_sums<T, S, 2> sums(sys); // E3, E5
        for (std::size_t i = 0; i < n; ++i) {
            const T e3 =
                m_bk[i] - T(tab::bhh1) * k[0][i] - T(tab::bhh2) * k[8][i] - T(tab::bhh3) * k[11][i];
            const T e5 = T(tab::er1) * k[0][i] + T(tab::er6) * k[5][i] + T(tab::er7) * k[6][i] +
                         T(tab::er8) * k[7][i] + T(tab::er9) * k[8][i] + T(tab::er10) * k[9][i] +
                         T(tab::er11) * k[10][i] + T(tab::er12) * k[11][i];
            sums.add(i, 0, e3 * m_inv[i]);
            sums.add(i, 1, e5 * m_inv[i]);
        }
        const auto norm = [&](const std::array<T, 2>& e, std::size_t components) {
            T deno = e[1] + T(0.01) * e[0];
            if (deno <= T(0)) deno = T(1);
            return abs(h) * e[1] * sqrt(T(1) / (T(components) * deno));
        };
        const T err = sums.largest(norm, n) * detail::unit_step_factor(m_layout, h);
        using std::isfinite;
        if (!isfinite(err) || !detail::all_finite(m_y1)) return {status::non_finite, err};
        return {status::ok, err};
    }

    ROTGEN_COLD outcome attempt_keeping_stages(const S& sys, T t, const vector& y, T h,
                                               step_stats& stats) {
        return steps(sys, t, y, h, stats, m_k);
    }

    ROTGEN_COLD bool accept_dense(const S& sys, step_stats& stats) {
        using detail::combination;
        using detail::stage;
        const T h = m_h;
        const T t = m_t;
        auto& k = m_k;
        detail::eval_rhs(sys, t + h, m_y1, k[12], stats); // k13 = f(t + h, y1)
        const bool finite = detail::all_finite(k[12]);
        if (finite) {
            auto a = [&](long double coefficient, int j) {
                return detail::make_term<T>(coefficient, k[static_cast<std::size_t>(j - 1)]);
            };
            // r1 = y0, r2 = y1 − y0, r3 = h k1 − r2, r4 = r2 − h k13 − r3
            for (std::size_t i = 0; i < detail::size_of(m_y0); ++i) {
                r(2)[i] = m_y1[i] - m_y0[i];
                r(3)[i] = h * k[0][i] - r(2)[i];
                r(4)[i] = r(2)[i] - h * k[12][i] - r(3)[i];
            }
            // three extra stages for the 7th-order extension
            work& arg = r(5);
            auto f = [&](int i, long double c) {
                detail::eval_rhs(sys, t + T(c) * h, arg, k[static_cast<std::size_t>(i - 1)], stats);
            };
            stage(arg, m_y0, h, a(tab::a1413, 13), a(tab::a141, 1), a(tab::a147, 7),
                  a(tab::a148, 8), a(tab::a149, 9), a(tab::a1410, 10), a(tab::a1411, 11),
                  a(tab::a1412, 12));
            f(14, tab::c14);
            stage(arg, m_y0, h, a(tab::a1514, 14), a(tab::a151, 1), a(tab::a156, 6),
                  a(tab::a157, 7), a(tab::a158, 8), a(tab::a1511, 11), a(tab::a1512, 12),
                  a(tab::a1513, 13));
            f(15, tab::c15);
            stage(arg, m_y0, h, a(tab::a1615, 15), a(tab::a161, 1), a(tab::a166, 6),
                  a(tab::a167, 7), a(tab::a168, 8), a(tab::a169, 9), a(tab::a1613, 13),
                  a(tab::a1614, 14));
            f(16, tab::c16);
            // r5..r8 = h Σ d_{4..7,j} k_j
            combination(r(5), a(tab::d41, 1), a(tab::d46, 6), a(tab::d47, 7), a(tab::d48, 8),
                        a(tab::d49, 9), a(tab::d410, 10), a(tab::d411, 11), a(tab::d412, 12),
                        a(tab::d413, 13), a(tab::d414, 14), a(tab::d415, 15), a(tab::d416, 16));
            combination(r(6), a(tab::d51, 1), a(tab::d56, 6), a(tab::d57, 7), a(tab::d58, 8),
                        a(tab::d59, 9), a(tab::d510, 10), a(tab::d511, 11), a(tab::d512, 12),
                        a(tab::d513, 13), a(tab::d514, 14), a(tab::d515, 15), a(tab::d516, 16));
            combination(r(7), a(tab::d61, 1), a(tab::d66, 6), a(tab::d67, 7), a(tab::d68, 8),
                        a(tab::d69, 9), a(tab::d610, 10), a(tab::d611, 11), a(tab::d612, 12),
                        a(tab::d613, 13), a(tab::d614, 14), a(tab::d615, 15), a(tab::d616, 16));
            combination(r(8), a(tab::d71, 1), a(tab::d76, 6), a(tab::d77, 7), a(tab::d78, 8),
                        a(tab::d79, 9), a(tab::d710, 10), a(tab::d711, 11), a(tab::d712, 12),
                        a(tab::d713, 13), a(tab::d714, 14), a(tab::d715, 15), a(tab::d716, 16));
            for (int j = 5; j <= 8; ++j)
                for (auto& v : r(j))
                    v *= h;
        }
        m_k1 = k[12]; // FSAL: k13 is the next step's k1
        return finite;
    }

    work& r(int i) { return m_r[static_cast<std::size_t>(i - 2)]; }
    const work& r(int i) const { return m_r[static_cast<std::size_t>(i - 2)]; }

    static T factor(const dop853<T>& m) {
        return calibration_factor(m.calibration_scale, m.calibration_power, m.rtol, m.atol);
    }

    T m_atol, m_rtol;
    error_layout m_layout;
    work m_bk, m_inv; ///< Σ b_j k_j and weight_i / sk_i of the last step (error_layout)
    bool m_fixed;     ///< fixed steps: no error estimate
    T m_t = T(0), m_h = T(0);
    work m_y0, m_y1, m_k1; ///< start and end of the step, f at the start
    stages m_k;            ///< the stages of the last step (with a static size: steps with samples)
    work m_y0_scratch, m_arg_scratch; ///< a run-time size's y0 and stage argument in a step
    std::array<work, 7> m_r;          ///< r2..r8
};

static_assert(check_method<dop853<double>>());

} // namespace rotgen
