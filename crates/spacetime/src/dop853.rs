//! Adaptive explicit Runge–Kutta integrator of order 8 with embedded 5th and 3rd order error
//! estimates and 7th-order dense output: DOP853 of Hairer, Nørsett & Wanner, "Solving
//! Ordinary Differential Equations I", 2nd ed., Springer 1993, Sec. II.10 (coefficients as
//! published with their Fortran code). Error norm and step-size control as in Sec. II.4
//! (eq. 4.11 and the step-size formula with safety factor 0.9).
//!
//! The state is a fixed-size array: a step allocates nothing. Dense output costs three extra
//! right-hand-side evaluations and is computed only when asked for ([`Dop853::dense`]).

// The coefficients are written as published (more digits than an f64 holds; each literal
// rounds to the f64 nearest the published value), and the component loops index several
// arrays of the state at once.
#![allow(clippy::excessive_precision, clippy::needless_range_loop)]

/// An autonomous ODE system y' = f(y) of dimension `N`.
pub trait OdeSystem<const N: usize> {
    fn rhs(&self, y: &[f64; N]) -> [f64; N];
}

/// Error tolerances and step bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance per component.
    pub rtol: f64,
    /// Absolute tolerance per component.
    pub atol: f64,
    /// Largest step allowed (also bounds the first step).
    pub h_max: f64,
    /// Below this step size a step counts as stalled and the integration fails.
    pub h_min: f64,
}

impl Default for Tolerances {
    /// The default: tight enough that constants of motion drift by < 1e-9 over a loop.
    fn default() -> Self {
        Tolerances {
            rtol: 1e-11,
            atol: 1e-11,
            h_max: f64::INFINITY,
            h_min: 1e-12,
        }
    }
}

/// What a step attempt ended with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepOutcome {
    /// A step was accepted; [`Dop853::lambda`] and [`Dop853::state`] moved on.
    Accepted,
    /// The step size fell below `h_min` (stalled) while the error stayed too large.
    Stalled,
    /// The right-hand side produced a non-finite value.
    NonFinite,
}

/// The dense-output polynomial of one accepted step, valid on [λ0, λ0 + h].
#[derive(Clone, Copy, Debug)]
pub struct DenseStep<const N: usize> {
    pub lambda0: f64,
    pub h: f64,
    pub y0: [f64; N],
    pub y1: [f64; N],
    f: [[f64; N]; 7],
    /// 1/h: the step's fraction s = (λ − λ₀)/h by a product (the match waits on it).
    per_h: f64,
}

impl<const N: usize> DenseStep<N> {
    /// The end of the step.
    pub fn lambda1(&self) -> f64 {
        self.lambda0 + self.h
    }
    /// The interpolated state at `lambda` (7th order; exact at both ends).
    pub fn eval(&self, lambda: f64) -> [f64; N] {
        self.eval_head::<N>(lambda)
    }

    /// The first `M` components of [`DenseStep::eval`], the others not computed (each
    /// component's polynomial is its own: the same values).
    pub fn eval_head<const M: usize>(&self, lambda: f64) -> [f64; M] {
        const { assert!(M <= N) };
        let s = (lambda - self.lambda0) * self.per_h;
        if lambda == self.lambda1() || s == 1.0 {
            // exact (the polynomial would be off by rounding)
            return std::array::from_fn(|i| self.y1[i]);
        }
        let s1 = 1.0 - s;
        // Hairer's CONTD8, f₀ + s₁(f₁ + s(f₂ + s₁(f₃ + s(f₄ + s₁(f₅ + s f₆))))), regrouped in
        // powers of p = s·s₁: (f₀ + s₁f₁) + p(f₂ + s₁f₃) + p²(f₄ + s₁f₅) + p³f₆. The chain of
        // dependent products is four deep instead of six (a falling ball's match waits on it,
        // step after step of its secant).
        let (p, f) = (s * s1, &self.f);
        let p2 = p * p;
        std::array::from_fn(|i| {
            let pair = |k: usize| f[k][i] + s1 * f[k + 1][i];
            let v = (pair(0) + p * pair(2)) + p2 * (pair(4) + p * f[6][i]);
            self.y0[i] + s * v
        })
    }
}

/// One accepted step: its ends only. Its dense output is made on demand by recomputing the
/// step's stages from `y0` ([`StepData::dense`]), which gives bit-identical values: the
/// many steps that never need an interpolant then cost nothing to keep.
#[derive(Clone, Copy, Debug)]
pub struct StepData<const N: usize> {
    pub lambda0: f64,
    pub h: f64,
    pub y0: [f64; N],
    pub y1: [f64; N],
}

impl<const N: usize> StepData<N> {
    pub fn lambda1(&self) -> f64 {
        self.lambda0 + self.h
    }

    /// The dense-output polynomial of this step: its 12 stages are recomputed from `y0`
    /// (16 evaluations of `sys` in all, only for the steps that need it).
    pub fn dense<S: OdeSystem<N>>(&self, sys: &S) -> DenseStep<N> {
        let mut k = [[0.0; N]; 13];
        k[0] = sys.rhs(&self.y0);
        let y_end = stages(sys, &self.y0, self.h, &mut k);
        debug_assert_eq!(
            y_end, self.y1,
            "a recomputed step must repeat itself exactly"
        );
        k[12] = sys.rhs(&self.y1);
        dense_poly(sys, self.lambda0, self.h, &self.y0, &self.y1, &k)
    }
}

/// Hairer's dense output of DOP853 for a step with stages `k13` (k[12] = f at its end):
/// three more stages, then the coefficients of the 7th-degree interpolant (CONTD8).
fn dense_poly<const N: usize, S: OdeSystem<N>>(
    sys: &S,
    lambda0: f64,
    h: f64,
    y0: &[f64; N],
    y1: &[f64; N],
    k13: &[[f64; N]; 13],
) -> DenseStep<N> {
    let mut k = [[0.0; N]; 16];
    k[..13].copy_from_slice(k13);
    k[13] = sys.rhs(&lincomb(
        y0,
        h,
        [
            (0, A[13][0]),
            (6, A[13][6]),
            (7, A[13][7]),
            (8, A[13][8]),
            (9, A[13][9]),
            (10, A[13][10]),
            (11, A[13][11]),
            (12, A[13][12]),
        ],
        &k,
    ));
    k[14] = sys.rhs(&lincomb(
        y0,
        h,
        [
            (0, A[14][0]),
            (5, A[14][5]),
            (6, A[14][6]),
            (7, A[14][7]),
            (10, A[14][10]),
            (11, A[14][11]),
            (12, A[14][12]),
            (13, A[14][13]),
        ],
        &k,
    ));
    k[15] = sys.rhs(&lincomb(
        y0,
        h,
        [
            (0, A[15][0]),
            (5, A[15][5]),
            (6, A[15][6]),
            (7, A[15][7]),
            (8, A[15][8]),
            (12, A[15][12]),
            (13, A[15][13]),
            (14, A[15][14]),
        ],
        &k,
    ));
    let mut f = [[0.0; N]; 7];
    for i in 0..N {
        let dy = y1[i] - y0[i];
        let bspl = h * k[0][i] - dy;
        f[0][i] = dy;
        f[1][i] = bspl;
        f[2][i] = dy - h * k[12][i] - bspl;
        for (row, d) in D.iter().enumerate() {
            let mut s = 0.0;
            for j in 0..16 {
                s += d[j] * k[j][i];
            }
            f[3 + row][i] = h * s;
        }
    }
    DenseStep {
        lambda0,
        h,
        y0: *y0,
        y1: *y1,
        f,
        per_h: 1.0 / h,
    }
}

/// The DOP853 integrator over a system `S` with state dimension `N`.
pub struct Dop853<const N: usize, S: OdeSystem<N>> {
    sys: S,
    tol: Tolerances,
    lambda: f64,
    y: [f64; N],
    f: [f64; N],
    h: f64,
    // Stages of the last accepted step (k[12] = f at its end), for dense output.
    k: [[f64; N]; 13],
    last_lambda: f64,
    last_h: f64,
    last_y: [f64; N],
    /// Accepted and rejected step counts.
    pub accepted: u64,
    pub rejected: u64,
    /// Right-hand side evaluations.
    pub evaluations: u64,
}

impl<const N: usize, S: OdeSystem<N>> Dop853<N, S> {
    /// Starts at parameter `lambda0` in state `y0`; the first step size is chosen
    /// automatically (Hairer et al., Sec. II.4) unless `h0` is given.
    pub fn new(sys: S, lambda0: f64, y0: [f64; N], tol: Tolerances, h0: Option<f64>) -> Self {
        let f = sys.rhs(&y0);
        let mut me = Dop853 {
            sys,
            tol,
            lambda: lambda0,
            y: y0,
            f,
            h: 0.0,
            k: [[0.0; N]; 13],
            last_lambda: lambda0,
            last_h: 0.0,
            last_y: y0,
            accepted: 0,
            rejected: 0,
            evaluations: 1,
        };
        // A state or step the arithmetic cannot handle (NaN, an overflowing estimate) gives
        // an infinite or NaN size here; `step` then reports it instead of retrying forever.
        me.h = h0.unwrap_or_else(|| me.initial_step()).min(tol.h_max);
        me
    }

    pub fn system(&self) -> &S {
        &self.sys
    }
    /// Current parameter value (end of the last accepted step).
    pub fn lambda(&self) -> f64 {
        self.lambda
    }
    /// Current state.
    pub fn state(&self) -> &[f64; N] {
        &self.y
    }
    /// Current derivative f(state).
    pub fn derivative(&self) -> &[f64; N] {
        &self.f
    }
    /// The step size the next attempt will use.
    pub fn next_step_size(&self) -> f64 {
        self.h
    }
    /// Caps the next step (e.g. to land exactly on a stop condition or stay near an object).
    pub fn limit_next_step(&mut self, h_cap: f64) {
        if h_cap > 0.0 && h_cap < self.h {
            self.h = h_cap;
        }
    }
    /// Parameter and state at the start of the last accepted step.
    pub fn previous(&self) -> (f64, &[f64; N]) {
        (self.last_lambda, &self.last_y)
    }

    fn scale(&self, a: &[f64; N], b: &[f64; N]) -> [f64; N] {
        let mut s = [0.0; N];
        for i in 0..N {
            s[i] = self.tol.atol + self.tol.rtol * a[i].abs().max(b[i].abs());
        }
        s
    }

    fn initial_step(&mut self) -> f64 {
        let sc = self.scale(&self.y, &self.y);
        let (mut d0, mut d1) = (0.0, 0.0);
        for i in 0..N {
            d0 += (self.y[i] / sc[i]).powi(2);
            d1 += (self.f[i] / sc[i]).powi(2);
        }
        let (d0, d1) = ((d0 / N as f64).sqrt(), (d1 / N as f64).sqrt());
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        let mut y1 = [0.0; N];
        for i in 0..N {
            y1[i] = self.y[i] + h0 * self.f[i];
        }
        let f1 = self.sys.rhs(&y1);
        self.evaluations += 1;
        let mut d2 = 0.0;
        for i in 0..N {
            d2 += ((f1[i] - self.f[i]) / sc[i]).powi(2);
        }
        let d2 = (d2 / N as f64).sqrt() / h0;
        let h1 = if d1.max(d2) <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).powf(1.0 / 8.0)
        };
        (100.0 * h0).min(h1)
    }

    /// Attempts steps until one is accepted or the integration cannot go on. Bounded: every
    /// retry shrinks a finite step by at least a factor 0.9 until it falls below `h_min`;
    /// an infinite or NaN step size (which shrinking never makes finite) ends the attempt
    /// at once.
    pub fn step(&mut self) -> StepOutcome {
        loop {
            let h = self.h;
            if !(h >= self.tol.h_min && h.is_finite()) {
                return StepOutcome::Stalled;
            }
            self.k[0] = self.f;
            let y_new = stages(&self.sys, &self.y, h, &mut self.k);
            self.evaluations += 11;
            if !y_new.iter().all(|v| v.is_finite()) {
                // Retry smaller: a step into a region the RHS cannot handle is not yet fatal.
                self.h *= 0.25;
                self.rejected += 1;
                if self.h < self.tol.h_min {
                    return StepOutcome::NonFinite;
                }
                continue;
            }
            let f_new = self.sys.rhs(&y_new);
            self.evaluations += 1;
            self.k[12] = f_new;
            let sc = self.scale(&self.y, &y_new);
            // Both error estimates use stages 0 and 5..=11 only (Hairer's ER and BHH weights).
            let s5 = lincomb(
                &[0.0; N],
                1.0,
                [
                    (0, E5[0]),
                    (5, E5[5]),
                    (6, E5[6]),
                    (7, E5[7]),
                    (8, E5[8]),
                    (9, E5[9]),
                    (10, E5[10]),
                    (11, E5[11]),
                ],
                &self.k,
            );
            let s3 = lincomb(
                &[0.0; N],
                1.0,
                [
                    (0, E3[0]),
                    (5, E3[5]),
                    (6, E3[6]),
                    (7, E3[7]),
                    (8, E3[8]),
                    (9, E3[9]),
                    (10, E3[10]),
                    (11, E3[11]),
                ],
                &self.k,
            );
            let (mut e5, mut e3) = (0.0, 0.0);
            for i in 0..N {
                e5 += (s5[i] / sc[i]).powi(2);
                e3 += (s3[i] / sc[i]).powi(2);
            }
            let err = if e5 == 0.0 && e3 == 0.0 {
                0.0
            } else {
                h * e5 / ((e5 + 0.01 * e3) * N as f64).sqrt()
            };
            if !err.is_finite() {
                self.h *= 0.25;
                self.rejected += 1;
                continue;
            }
            if err <= 1.0 {
                let factor = if err == 0.0 {
                    10.0
                } else {
                    (0.9 * inv_eighth_root(err)).clamp(0.2, 10.0)
                };
                self.last_lambda = self.lambda;
                self.last_h = h;
                self.last_y = self.y;
                self.lambda += h;
                self.y = y_new;
                self.f = f_new;
                // Kept finite: an infinite step could never be shrunk back.
                self.h = (h * factor).min(self.tol.h_max).min(f64::MAX);
                self.accepted += 1;
                return StepOutcome::Accepted;
            }
            self.rejected += 1;
            self.h = h * (0.9 * inv_eighth_root(err)).clamp(0.2, 1.0);
        }
    }

    /// The last accepted step (its ends): its dense output can be made later.
    pub fn last_step(&self) -> StepData<N> {
        StepData {
            lambda0: self.last_lambda,
            h: self.last_h,
            y0: self.last_y,
            y1: self.y,
        }
    }

    /// Dense output of the last accepted step (three extra evaluations).
    pub fn dense(&mut self) -> DenseStep<N> {
        self.evaluations += 3;
        dense_poly(
            &self.sys,
            self.last_lambda,
            self.last_h,
            &self.last_y,
            &self.y,
            &self.k,
        )
    }
}

/// The stages k[1..=11] of one DOP853 step of size `h` from `y` (k[0] = f(y) given), with
/// their non-zero coefficients only, as straight-line code; returns the 8th-order solution
/// at the end of the step. Shared by [`Dop853::step`] and [`StepData::dense`], so that a
/// step recomputed later gives bit-identical stages.
#[inline(always)]
fn stages<const N: usize, S: OdeSystem<N>>(
    sys: &S,
    y: &[f64; N],
    h: f64,
    k: &mut [[f64; N]; 13],
) -> [f64; N] {
    k[1] = sys.rhs(&lincomb(y, h, [(0, A[1][0])], k));
    k[2] = sys.rhs(&lincomb(y, h, [(0, A[2][0]), (1, A[2][1])], k));
    k[3] = sys.rhs(&lincomb(y, h, [(0, A[3][0]), (2, A[3][2])], k));
    k[4] = sys.rhs(&lincomb(
        y,
        h,
        [(0, A[4][0]), (2, A[4][2]), (3, A[4][3])],
        k,
    ));
    k[5] = sys.rhs(&lincomb(
        y,
        h,
        [(0, A[5][0]), (3, A[5][3]), (4, A[5][4])],
        k,
    ));
    k[6] = sys.rhs(&lincomb(
        y,
        h,
        [(0, A[6][0]), (3, A[6][3]), (4, A[6][4]), (5, A[6][5])],
        k,
    ));
    k[7] = sys.rhs(&lincomb(
        y,
        h,
        [
            (0, A[7][0]),
            (3, A[7][3]),
            (4, A[7][4]),
            (5, A[7][5]),
            (6, A[7][6]),
        ],
        k,
    ));
    k[8] = sys.rhs(&lincomb(
        y,
        h,
        [
            (0, A[8][0]),
            (3, A[8][3]),
            (4, A[8][4]),
            (5, A[8][5]),
            (6, A[8][6]),
            (7, A[8][7]),
        ],
        k,
    ));
    k[9] = sys.rhs(&lincomb(
        y,
        h,
        [
            (0, A[9][0]),
            (3, A[9][3]),
            (4, A[9][4]),
            (5, A[9][5]),
            (6, A[9][6]),
            (7, A[9][7]),
            (8, A[9][8]),
        ],
        k,
    ));
    k[10] = sys.rhs(&lincomb(
        y,
        h,
        [
            (0, A[10][0]),
            (3, A[10][3]),
            (4, A[10][4]),
            (5, A[10][5]),
            (6, A[10][6]),
            (7, A[10][7]),
            (8, A[10][8]),
            (9, A[10][9]),
        ],
        k,
    ));
    k[11] = sys.rhs(&lincomb(
        y,
        h,
        [
            (0, A[11][0]),
            (3, A[11][3]),
            (4, A[11][4]),
            (5, A[11][5]),
            (6, A[11][6]),
            (7, A[11][7]),
            (8, A[11][8]),
            (9, A[11][9]),
            (10, A[11][10]),
        ],
        k,
    ));
    lincomb(
        y,
        h,
        [
            (0, B[0]),
            (5, B[5]),
            (6, B[6]),
            (7, B[7]),
            (8, B[8]),
            (9, B[9]),
            (10, B[10]),
            (11, B[11]),
        ],
        k,
    )
}

/// y + h Σ c_j k_j over the listed (j, c_j): a fixed-size list per stage, so the compiler
/// unrolls and vectorizes it.
#[inline(always)]
fn lincomb<const N: usize, const M: usize, const K: usize>(
    y: &[f64; N],
    h: f64,
    terms: [(usize, f64); M],
    k: &[[f64; N]; K],
) -> [f64; N] {
    // Two interleaved sums: a step is latency-bound (each stage waits for the previous),
    // and one running sum would chain all M additions.
    let (mut even, mut odd) = ([0.0; N], [0.0; N]);
    for (n, (j, c)) in terms.into_iter().enumerate() {
        let acc = if n % 2 == 0 { &mut even } else { &mut odd };
        for i in 0..N {
            acc[i] += c * k[j][i];
        }
    }
    let mut out = *y;
    for i in 0..N {
        out[i] += h * (even[i] + odd[i]);
    }
    out
}

// Butcher tableau of DOP853 (rows 12..=15: the FSAL stage and the three dense-output stages).
#[rustfmt::skip]
const A: [[f64; 16]; 16] = {
    let mut a = [[0.0; 16]; 16];
    a[1][0] = 5.26001519587677318785587544488e-2;
    a[2][0] = 1.97250569845378994544595329183e-2;
    a[2][1] = 5.91751709536136983633785987549e-2;
    a[3][0] = 2.95875854768068491816892993775e-2;
    a[3][2] = 8.87627564304205475450678981324e-2;
    a[4][0] = 2.41365134159266685502369798665e-1;
    a[4][2] = -8.84549479328286085344864962717e-1;
    a[4][3] = 9.24834003261792003115737966543e-1;
    a[5][0] = 3.7037037037037037037037037037e-2;
    a[5][3] = 1.70828608729473871279604482173e-1;
    a[5][4] = 1.25467687566822425016691814123e-1;
    a[6][0] = 3.7109375e-2;
    a[6][3] = 1.70252211019544039314978060272e-1;
    a[6][4] = 6.02165389804559606850219397283e-2;
    a[6][5] = -1.7578125e-2;
    a[7][0] = 3.70920001185047927108779319836e-2;
    a[7][3] = 1.70383925712239993810214054705e-1;
    a[7][4] = 1.07262030446373284651809199168e-1;
    a[7][5] = -1.53194377486244017527936158236e-2;
    a[7][6] = 8.27378916381402288758473766002e-3;
    a[8][0] = 6.24110958716075717114429577812e-1;
    a[8][3] = -3.36089262944694129406857109825;
    a[8][4] = -8.68219346841726006818189891453e-1;
    a[8][5] = 2.75920996994467083049415600797e1;
    a[8][6] = 2.01540675504778934086186788979e1;
    a[8][7] = -4.34898841810699588477366255144e1;
    a[9][0] = 4.77662536438264365890433908527e-1;
    a[9][3] = -2.48811461997166764192642586468;
    a[9][4] = -5.90290826836842996371446475743e-1;
    a[9][5] = 2.12300514481811942347288949897e1;
    a[9][6] = 1.52792336328824235832596922938e1;
    a[9][7] = -3.32882109689848629194453265587e1;
    a[9][8] = -2.03312017085086261358222928593e-2;
    a[10][0] = -9.3714243008598732571704021658e-1;
    a[10][3] = 5.18637242884406370830023853209;
    a[10][4] = 1.09143734899672957818500254654;
    a[10][5] = -8.14978701074692612513997267357;
    a[10][6] = -1.85200656599969598641566180701e1;
    a[10][7] = 2.27394870993505042818970056734e1;
    a[10][8] = 2.49360555267965238987089396762;
    a[10][9] = -3.0467644718982195003823669022;
    a[11][0] = 2.27331014751653820792359768449;
    a[11][3] = -1.05344954667372501984066689879e1;
    a[11][4] = -2.00087205822486249909675718444;
    a[11][5] = -1.79589318631187989172765950534e1;
    a[11][6] = 2.79488845294199600508499808837e1;
    a[11][7] = -2.85899827713502369474065508674;
    a[11][8] = -8.87285693353062954433549289258;
    a[11][9] = 1.23605671757943030647266201528e1;
    a[11][10] = 6.43392746015763530355970484046e-1;
    a[12][0] = 5.42937341165687622380535766363e-2;
    a[12][5] = 4.45031289275240888144113950566;
    a[12][6] = 1.89151789931450038304281599044;
    a[12][7] = -5.8012039600105847814672114227;
    a[12][8] = 3.1116436695781989440891606237e-1;
    a[12][9] = -1.52160949662516078556178806805e-1;
    a[12][10] = 2.01365400804030348374776537501e-1;
    a[12][11] = 4.47106157277725905176885569043e-2;
    a[13][0] = 5.61675022830479523392909219681e-2;
    a[13][6] = 2.53500210216624811088794765333e-1;
    a[13][7] = -2.46239037470802489917441475441e-1;
    a[13][8] = -1.24191423263816360469010140626e-1;
    a[13][9] = 1.5329179827876569731206322685e-1;
    a[13][10] = 8.20105229563468988491666602057e-3;
    a[13][11] = 7.56789766054569976138603589584e-3;
    a[13][12] = -8.298e-3;
    a[14][0] = 3.18346481635021405060768473261e-2;
    a[14][5] = 2.83009096723667755288322961402e-2;
    a[14][6] = 5.35419883074385676223797384372e-2;
    a[14][7] = -5.49237485713909884646569340306e-2;
    a[14][10] = -1.08347328697249322858509316994e-4;
    a[14][11] = 3.82571090835658412954920192323e-4;
    a[14][12] = -3.40465008687404560802977114492e-4;
    a[14][13] = 1.41312443674632500278074618366e-1;
    a[15][0] = -4.28896301583791923408573538692e-1;
    a[15][5] = -4.69762141536116384314449447206;
    a[15][6] = 7.68342119606259904184240953878;
    a[15][7] = 4.06898981839711007970213554331;
    a[15][8] = 3.56727187455281109270669543021e-1;
    a[15][12] = -1.39902416515901462129418009734e-3;
    a[15][13] = 2.9475147891527723389556272149;
    a[15][14] = -9.15095847217987001081870187138;
    a
};

/// 8th-order weights (row 12 of the tableau, stages 0..12).
const B: [f64; 12] = {
    let mut b = [0.0; 12];
    let mut j = 0;
    while j < 12 {
        b[j] = A[12][j];
        j += 1;
    }
    b
};

/// Weights of the 8th − 3rd order error estimate (13 stages, the last being FSAL).
const E3: [f64; 13] = {
    let mut e = [0.0; 13];
    let mut j = 0;
    while j < 12 {
        e[j] = B[j];
        j += 1;
    }
    e[0] -= 0.244094488188976377952755905512;
    e[8] -= 0.733846688281611857341361741547;
    e[11] -= 0.220588235294117647058823529412e-1;
    e
};

// The error estimate above skips stages 1..=4 and 12: their weights must be zero.
const _: () = {
    let mut j = 1;
    while j < 13 {
        if j < 5 || j == 12 {
            assert!(E3[j] == 0.0 && E5[j] == 0.0);
        }
        j += 1;
    }
};

/// Weights of the 8th − 5th order error estimate.
#[rustfmt::skip]
const E5: [f64; 13] = [
    0.1312004499419488073250102996e-1, 0.0, 0.0, 0.0, 0.0,
    -0.1225156446376204440720569753e1, -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1, -0.3503288487499736816886487290,
    0.3341791187130174790297318841, 0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1, 0.0,
];

/// Dense-output coefficients for the polynomial terms 4..7.
#[rustfmt::skip]
const D: [[f64; 16]; 4] = [
    [-0.84289382761090128651353491142e1, 0.0, 0.0, 0.0, 0.0, 0.56671495351937776962531783590,
     -0.30689499459498916912797304727e1, 0.23846676565120698287728149680e1, 0.21170345824450282767155149946e1,
     -0.87139158377797299206789907490, 0.22404374302607882758541771650e1, 0.63157877876946881815570249290,
     -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e2, -0.91946323924783554000451984436e1,
     -0.44360363875948939664310572000e1],
    [0.10427508642579134603413151009e2, 0.0, 0.0, 0.0, 0.0, 0.24228349177525818288430175319e3,
     0.16520045171727028198505394887e3, -0.37454675472269020279518312152e3, -0.22113666853125306036270938578e2,
     0.77334326684722638389603898808e1, -0.30674084731089398182061213626e2, -0.93321305264302278729567221706e1,
     0.15697238121770843886131091075e2, -0.31139403219565177677282850411e2, -0.93529243588444783865713862664e1,
     0.35816841486394083752465898540e2],
    [0.19985053242002433820987653617e2, 0.0, 0.0, 0.0, 0.0, -0.38703730874935176555105901742e3,
     -0.18917813819516756882830838328e3, 0.52780815920542364900561016686e3, -0.11573902539959630126141871134e2,
     0.68812326946963000169666922661e1, -0.10006050966910838403183860980e1, 0.77771377980534432092869265740,
     -0.27782057523535084065932004339e1, -0.60196695231264120758267380846e2, 0.84320405506677161018159903784e2,
     0.11992291136182789328035130030e2],
    [-0.25693933462703749003312586129e2, 0.0, 0.0, 0.0, 0.0, -0.15418974869023643374053993627e3,
     -0.23152937917604549567536039109e3, 0.35763911791061412378285349910e3, 0.93405324183624310003907691704e2,
     -0.37458323136451633156875139351e2, 0.10409964950896230045147246184e3, 0.29840293426660503123344363579e2,
     -0.43533456590011143754432175058e2, 0.96324553959188282948394950600e2, -0.39177261675615439165231486172e2,
     -0.14972683625798562581422125276e3],
];

/// x^(−1/8) by three square roots: the step-size controller's factor (Hairer et al.,
/// eq. II.4.13 with order 8), several times cheaper than `powf`.
#[inline]
fn inv_eighth_root(x: f64) -> f64 {
    1.0 / x.sqrt().sqrt().sqrt()
}
