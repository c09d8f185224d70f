//! `dop853`: the explicit Runge–Kutta method of Dormand and Prince of order 8 with embedded
//! error estimators of orders 5 and 3, adaptive step size and a 7th-order dense output.
//!
//! One step of size `h` from `(t, y)` evaluates twelve stages
//!
//! ```text
//! k_s = f(t + c_s h, y + h Σ_{j<s} a_sj k_j),    s = 1..12,
//! y_new = y + h Σ b_j k_j                          (order 8; b_j = a_13,j)
//! ```
//!
//! and two error estimates, `e5 = h Σ E5_j k_j` (order 5) and `e3 = h Σ E3_j k_j` (order 3),
//! combined as in Hairer's code: with the weights `sk_i = atol + rtol max(|y_i|, |y_new,i|)`
//! and the norms `|e|² = Σ (e_i / sk_i)²`,
//!
//! ```text
//! err = |e5|² / sqrt(n (|e5|² + 0.01 |e3|²))
//! ```
//!
//! (the 3rd-order estimate keeps the 5th-order one honest when it happens to be small). The
//! step is accepted when `err <= 1`; the next step is `h / fac` with
//! `fac = clamp(err^(1/8) / 0.9, 1/6, 1/0.333)`, and after a rejection it may not grow. The
//! first step is Hairer's `hinit` guess (one extra evaluation). `k_1` of a step is the
//! derivative at the end of the previous one (first same as last), so an accepted step costs
//! 12 evaluations and a rejected one 11.
//!
//! **Dense output** (order 7): three more stages (`k_14..k_16`) give the continuous solution
//! on `[t, t + h]`, with `s = (τ - t)/h`, `s' = 1 - s`,
//!
//! ```text
//! y(τ) = r1 + s (r2 + s' (r3 + s (r4 + s' (r5 + s (r6 + s' (r7 + s r8))))))
//! r1 = y, r2 = y_new - y, r3 = h k_1 - r2, r4 = r2 - h f(t + h, y_new) - r3,
//! r(5+m) = h Σ_j D_mj k_j   (m = 0..3, over the 16 stages),
//! ```
//!
//! computed only for steps that contain an output time (three evaluations each).
//!
//! **On the fixed-step API** `dt` is the spacing of the output samples: [`Dop853`] steps with
//! its own step sizes and interpolates each sample of the grid from the step that contains
//! it, so a run stores exactly the samples (times, count, strides) every other method stores.
//! The last step is shortened to land on `t1`, so the final state (the one a continuing
//! call starts from) is a step's result, accurate to the 8th-order solution, never an
//! interpolation.
//!
//! Coefficients: E. Hairer's `dop853.f` (the code of Hairer, Nørsett & Wanner, *Solving
//! Ordinary Differential Equations I*, 2nd ed., Springer 1993, §II.10), as also published in
//! SciPy's `dop853_coefficients.py`; the method is P. J. Prince & J. R. Dormand, "High order
//! embedded Runge–Kutta formulae", J. Comput. Appl. Math. 7 (1981) 67–75. They are kept to
//! the source's 30 digits (rounded to the nearest double by the compiler).
//!
//! Not symplectic: on conservative systems the energy error follows the tolerance (it drifts,
//! slowly, at tight tolerances). Allocation-free after construction.

use std::collections::BTreeMap;

use super::field::VectorField;
use super::stepper::{AdaptiveStepper, FieldStepper, Report};
use crate::classical::core::method::{MethodInfo, Scheme};
use crate::classical::core::{Error, ExtraValue, Result};
use crate::classical::integrators::Tolerances;

/// The facts about `dop853`.
pub const INFO: MethodInfo = MethodInfo {
    name: "dop853",
    label: "DOP853",
    summary: "Dormand–Prince 8(5,3): adaptive steps to rtol/atol, samples from its \
              7th-order dense output; energy drifts",
    order: 8,
    symplectic: false,
    separable_only: false,
    evaluations_per_step: 12,
    evaluations: "right-hand-side evaluations per accepted step, exact (11 stages and the \
                  derivative at the new state, reused as the next step's first stage); 11 per \
                  rejected step, 3 more per step whose dense output gives a sample, and 2 to \
                  start (the first derivative and the first-step guess)",
    reference: "P. J. Prince, J. R. Dormand, J. Comput. Appl. Math. 7 (1981) 67–75; Hairer, \
                Nørsett, Wanner, Solving ODEs I (2nd ed. 1993), §II.10 (code DOP853)",
    scheme: Scheme::Adaptive,
};

/// Stages of one step (the 13th slot holds the derivative at the new state).
const STAGES: usize = 12;
/// All stage slots: the 12 stages, the derivative at the new state, three for dense output.
const SLOTS: usize = 16;

/// Nodes `c_s` of the 16 stages (the 13th is the end of the step).
#[allow(clippy::excessive_precision)]
const C: [f64; SLOTS] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
    1.0,
    0.1,
    0.2,
    0.777777777777777777777777777778,
];

/// Coupling coefficients `a_sj` (row `s` uses slots `j < s`). Row 12 is `b`, the weights of
/// the 8th-order solution; rows 13–15 are the dense-output stages, which also use the
/// derivative at the new state (slot 12).
#[allow(clippy::excessive_precision)]
const A: [[f64; SLOTS]; SLOTS] = {
    let mut a = [[0.0; SLOTS]; SLOTS];
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

/// Weights of the 8th-order solution (row 12 of [`A`]).
const B: [f64; STAGES] = {
    let mut b = [0.0; STAGES];
    let mut j = 0;
    while j < STAGES {
        b[j] = A[STAGES][j];
        j += 1;
    }
    b
};

/// Weights of the 5th-order error estimate `e5 = h Σ E5_j k_j` (Hairer's `er1 .. er12`).
#[allow(clippy::excessive_precision)]
const E5: [f64; STAGES] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];

/// Hairer's `bhh1, bhh2, bhh3`: the 3rd-order estimate is `e3 = h (Σ b_j k_j - bhh1 k_1 -
/// bhh2 k_9 - bhh3 k_12)`.
#[allow(clippy::excessive_precision)]
const BHH: [f64; 3] = [
    0.244094488188976377952755905512,
    0.733846688281611857341361741547,
    0.220588235294117647058823529412e-1,
];

/// Weights of the 3rd-order error estimate, `E3 = b - bhh` on stages 1, 9 and 12.
const E3: [f64; STAGES] = {
    let mut e = B;
    e[0] -= BHH[0];
    e[8] -= BHH[1];
    e[11] -= BHH[2];
    e
};

/// Dense-output coefficients `D_mj` of `r5 .. r8` over the 16 slots (Hairer's `d41 ..
/// d716`).
#[allow(clippy::excessive_precision)]
const D: [[f64; SLOTS]; 4] = [
    [
        -0.84289382761090128651353491142e1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.56671495351937776962531783590,
        -0.30689499459498916912797304727e1,
        0.23846676565120698287728149680e1,
        0.21170345824450282767155149946e1,
        -0.87139158377797299206789907490,
        0.22404374302607882758541771650e1,
        0.63157877876946881815570249290,
        -0.88990336451333310820698117400e-1,
        0.18148505520854727256656404962e2,
        -0.91946323924783554000451984436e1,
        -0.44360363875948939664310572000e1,
    ],
    [
        0.10427508642579134603413151009e2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.24228349177525818288430175319e3,
        0.16520045171727028198505394887e3,
        -0.37454675472269020279518312152e3,
        -0.22113666853125306036270938578e2,
        0.77334326684722638389603898808e1,
        -0.30674084731089398182061213626e2,
        -0.93321305264302278729567221706e1,
        0.15697238121770843886131091075e2,
        -0.31139403219565177677282850411e2,
        -0.93529243588444783865713862664e1,
        0.35816841486394083752465898540e2,
    ],
    [
        0.19985053242002433820987653617e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.38703730874935176555105901742e3,
        -0.18917813819516756882830838328e3,
        0.52780815920542364900561016686e3,
        -0.11573902539959630126141871134e2,
        0.68812326946963000169666922661e1,
        -0.10006050966910838403183860980e1,
        0.77771377980534432092869265740,
        -0.27782057523535084065932004339e1,
        -0.60196695231264120758267380846e2,
        0.84320405506677161018159903784e2,
        0.11992291136182789328035130030e2,
    ],
    [
        -0.25693933462703749003312586129e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.15418974869023643374053993627e3,
        -0.23152937917604549567536039109e3,
        0.35763911791061412378285349910e3,
        0.93405324183624310003907691704e2,
        -0.37458323136451633156875139351e2,
        0.10409964950896230045147246184e3,
        0.29840293426660503123344363579e2,
        -0.43533456590011143754432175058e2,
        0.96324553959188282948394950600e2,
        -0.39177261675615439165231486172e2,
        -0.14972683625798562581422125276e3,
    ],
];

/// Safety factor of the step-size controller (Hairer's `safe`).
const SAFE: f64 = 0.9;
/// Largest shrink of the step in one rejection or acceptance, `1/0.333` (Hairer's `fac1`).
const MAX_SHRINK: f64 = 1.0 / 0.333;
/// Smallest `h / h_new`: the step grows at most sixfold (Hairer's `fac2 = 6`).
const MIN_SHRINK: f64 = 1.0 / 6.0;
/// Exponent of the controller, `1/8` for the order-8 solution (Hairer's `expo1`, `beta = 0`).
const EXPONENT: f64 = 1.0 / 8.0;
/// Two times within this many ulps of each other are the same output time: the drivers'
/// `t_i + dt` and `t_{i+1} = t0 + (i + 1) dt` differ by rounding.
const SAME_TIME_ULPS: f64 = 8.0;

/// The `dop853` stepper: its tolerances, the internal solution (time, state, step-size
/// proposal, the last step's stages for dense output) and all work buffers, allocated once.
///
/// As a [`FieldStepper`] (`step_field(f, t, y, h)`), it moves the output `y` from `t` to
/// `t + h` by as many internal steps as the tolerances need, interpolating at `t + h`. It
/// continues its internal solution when called from where it last left the output (the same
/// time, up to rounding, and the same state), and restarts from `(t, y)` otherwise, so a
/// caller may change the state between calls.
#[derive(Debug, Clone)]
pub struct Dop853 {
    dim: usize,
    tolerances: Tolerances,
    bound: Option<f64>,
    /// Stage derivatives, slot-major: slot `s` is `k[s*dim..(s+1)*dim]`.
    k: Vec<f64>,
    /// The internal solution at `t`.
    y: Vec<f64>,
    /// The state at the start of the last accepted step (`t_old`).
    y_old: Vec<f64>,
    /// Candidate state of a step, then a scratch buffer.
    y_new: Vec<f64>,
    /// Argument of a stage evaluation.
    stage: Vec<f64>,
    /// `r2 .. r8` of the last accepted step, when `dense_ready`.
    dense: Vec<f64>,
    dense_ready: bool,
    /// The output the caller was last given, to recognize a continuing call.
    out: Vec<f64>,
    out_t: f64,
    started: bool,
    /// `k[12]` holds the derivative at `y` (the last step was accepted) and must move to
    /// slot 0 before the next step.
    fsal_pending: bool,
    direction: f64,
    t: f64,
    t_old: f64,
    h_old: f64,
    h: f64,
    last_rejected: bool,
    accepted: u64,
    rejected: u64,
    evaluations: u64,
}

impl Dop853 {
    /// A stepper for `dim`-component states with `tolerances` (not validated here: the drivers
    /// validate [`IntegrateOptions::tolerances`](crate::classical::IntegrateOptions)), not
    /// stepping past `bound` (`None`: unbounded).
    pub fn new(dim: usize, tolerances: Tolerances, bound: Option<f64>) -> Self {
        Self {
            dim,
            tolerances,
            bound,
            k: vec![0.0; SLOTS * dim],
            y: vec![0.0; dim],
            y_old: vec![0.0; dim],
            y_new: vec![0.0; dim],
            stage: vec![0.0; dim],
            dense: vec![0.0; 7 * dim],
            dense_ready: false,
            out: vec![0.0; dim],
            out_t: f64::NAN,
            started: false,
            fsal_pending: false,
            direction: 1.0,
            t: 0.0,
            t_old: 0.0,
            h_old: 0.0,
            h: 0.0,
            last_rejected: false,
            accepted: 0,
            rejected: 0,
            evaluations: 0,
        }
    }

    /// Accepted steps so far.
    pub fn accepted_steps(&self) -> u64 {
        self.accepted
    }

    /// Rejected steps so far.
    pub fn rejected_steps(&self) -> u64 {
        self.rejected
    }

    /// Right-hand-side evaluations so far.
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// Moves the output `y` from `t` to `t + h` (see the type's docs).
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`] when the step size underflows (at `t` relative to the
    /// rounding of `t`), the error estimate is not finite (the field returned NaN or infinity
    /// where no smaller step avoids it) or the step budget
    /// ([`Tolerances::max_steps`]) is spent; [`Error::InvalidArgument`] for a target beyond the
    /// bound; whatever the field's evaluation returns.
    pub fn advance<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        if h == 0.0 {
            return Ok(());
        }
        let direction = h.signum();
        let continuing = self.started
            && (direction > 0.0) == (self.direction > 0.0)
            && same_time(t, self.out_t)
            && y.iter().zip(&self.out).all(|(a, b)| a.to_bits() == b.to_bits());
        if !continuing {
            self.restart(f, t, y, direction)?;
        }
        let mut target = t + h;
        if let Some(bound) = self.bound {
            if same_time(target, bound) {
                target = bound;
            } else if (target - bound) * direction > 0.0 {
                return Err(Error::InvalidArgument {
                    name: "h".into(),
                    reason: format!(
                        "t + h = {target} is beyond the end {bound} this stepper was built for"
                    ),
                });
            }
        }
        while (target - self.t) * direction > 0.0 {
            self.step(f)?;
        }
        // Exactly on the last step's end (the bound): the step's own state.
        if target.to_bits() == self.t.to_bits() {
            y.copy_from_slice(&self.y);
        } else {
            self.interpolate(f, target, y)?;
        }
        self.out.copy_from_slice(y);
        self.out_t = target;
        Ok(())
    }

    /// One step of the 8th-order formula of size `h` from `(t, y)`, without error control or
    /// dense output (12 evaluations): for measuring the formula's order, or as a fixed-step
    /// 8th-order Runge–Kutta method. The next [`advance`](Self::advance) restarts.
    ///
    /// # Errors
    /// Whatever the field's evaluation returns.
    pub fn step_fixed<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.started = false;
        self.fsal_pending = false;
        self.y.copy_from_slice(y);
        self.t = t;
        f.eval(t, &self.y, &mut self.k[..self.dim])?;
        self.evaluations += 1;
        self.stages(f, h)?;
        y.copy_from_slice(&self.y_new);
        Ok(())
    }

    /// Starts the internal solution at `(t, y)`: the derivative there and the first step.
    fn restart<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &[f64],
        direction: f64,
    ) -> Result<()> {
        self.y.copy_from_slice(y);
        self.t = t;
        self.direction = direction;
        self.dense_ready = false;
        self.fsal_pending = false;
        self.last_rejected = false;
        self.started = false;
        let n = self.dim;
        f.eval(t, &self.y, &mut self.k[..n])?;
        self.evaluations += 1;
        self.h = self.initial_step(f)?;
        self.started = true;
        Ok(())
    }

    /// Hairer's `hinit`: a first step from the sizes of `y` and `f(t, y)` and a difference
    /// estimate of the second derivative (one evaluation).
    fn initial_step<F: VectorField + ?Sized>(&mut self, f: &F) -> Result<f64> {
        let n = self.dim;
        let Tolerances { rtol, atol, .. } = self.tolerances;
        let max_step = self.max_step();
        let (k0, rest) = self.k.split_at_mut(n);
        let (mut dnf, mut dny) = (0.0, 0.0);
        for (yi, fi) in self.y.iter().zip(k0.iter()) {
            let sk = atol + rtol * yi.abs();
            dnf += (fi / sk) * (fi / sk);
            dny += (yi / sk) * (yi / sk);
        }
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        h = h.min(max_step);
        let hs = h * self.direction;
        for ((s, yi), fi) in self.stage.iter_mut().zip(&self.y).zip(k0.iter()) {
            *s = yi + hs * fi;
        }
        let f1 = &mut rest[..n];
        f.eval(self.t + hs, &self.stage, f1)?;
        self.evaluations += 1;
        let mut der2 = 0.0;
        for ((a, b), yi) in f1.iter().zip(k0.iter()).zip(&self.y) {
            let sk = atol + rtol * yi.abs();
            der2 += ((a - b) / sk) * ((a - b) / sk);
        }
        let der2 = der2.sqrt() / h;
        let der12 = der2.max(dnf.sqrt());
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(EXPONENT)
        };
        let h = (100.0 * h).min(h1).min(max_step);
        if h.is_finite() && h > 0.0 {
            Ok(h * self.direction)
        } else {
            Err(self.failure(h, "the first step size is not finite and positive"))
        }
    }

    /// The largest step: up to the bound, unlimited without one.
    fn max_step(&self) -> f64 {
        self.bound
            .map_or(f64::INFINITY, |b| (b - self.t).abs().max(f64::MIN_POSITIVE))
    }

    fn failure(&self, step: f64, reason: &str) -> Error {
        Error::StepSizeTooSmall {
            t: self.t,
            step,
            reason: reason.into(),
        }
    }

    /// One accepted step (after as many rejected ones as needed) from `self.t`.
    fn step<F: VectorField + ?Sized>(&mut self, f: &F) -> Result<()> {
        let n = self.dim;
        if self.fsal_pending {
            self.k.copy_within(STAGES * n..(STAGES + 1) * n, 0);
            self.fsal_pending = false;
        }
        let mut nonfinite = false;
        loop {
            if self.accepted + self.rejected >= self.tolerances.max_steps {
                return Err(self.failure(
                    self.h,
                    &format!(
                        "the budget of {} steps (max_steps) is spent; raise it, loosen rtol/atol \
                         or split the span",
                        self.tolerances.max_steps
                    ),
                ));
            }
            let mut h = self.h;
            let mut last = false;
            if let Some(bound) = self.bound {
                // Hairer's rule: a step that would leave less than 1% of itself before the
                // bound is stretched onto it, so no sliver of a step remains.
                if (self.t + 1.01 * h - bound) * self.direction > 0.0 {
                    h = bound - self.t;
                    last = true;
                }
            }
            if 0.1 * h.abs() <= self.t.abs() * f64::EPSILON || h.abs() < f64::MIN_POSITIVE {
                return Err(self.failure(
                    h,
                    if nonfinite {
                        "the error estimate is not finite (the right-hand side returned NaN \
                         or infinity) at every step size down to the rounding of t"
                    } else {
                        "the step size fell below the rounding of t to meet the tolerances"
                    },
                ));
            }
            self.stages(f, h)?;
            let err = self.error_norm(h);
            let fac11 = err.powf(EXPONENT);
            if err <= 1.0 {
                let fac = (fac11 / SAFE).clamp(MIN_SHRINK, MAX_SHRINK);
                let mut h_new = h / fac;
                if self.last_rejected {
                    h_new = self.direction * h_new.abs().min(h.abs());
                }
                self.last_rejected = false;
                let t_new = if last { self.bound.unwrap_or(self.t + h) } else { self.t + h };
                // Accept: y_old <- y, y <- y_new.
                std::mem::swap(&mut self.y_old, &mut self.y);
                std::mem::swap(&mut self.y, &mut self.y_new);
                f.eval(t_new, &self.y, &mut self.k[STAGES * n..(STAGES + 1) * n])?;
                self.evaluations += 1;
                self.fsal_pending = true;
                self.dense_ready = false;
                self.t_old = self.t;
                self.h_old = h;
                self.t = t_new;
                self.h = h_new;
                self.accepted += 1;
                return Ok(());
            }
            nonfinite |= !err.is_finite();
            let shrink = if fac11.is_nan() {
                MAX_SHRINK
            } else {
                MAX_SHRINK.min(fac11 / SAFE)
            };
            self.h = h / shrink;
            self.last_rejected = true;
            self.rejected += 1;
        }
    }

    /// Evaluates stages 2..12 of a step of size `h` from `(t, y)` (stage 1 is in slot 0) and
    /// writes the 8th-order candidate into `y_new`.
    fn stages<F: VectorField + ?Sized>(&mut self, f: &F, h: f64) -> Result<()> {
        let n = self.dim;
        for s in 1..STAGES {
            combine(&mut self.stage, &self.y, h, &A[s][..s], &self.k);
            f.eval(
                self.t + C[s] * h,
                &self.stage,
                &mut self.k[s * n..(s + 1) * n],
            )?;
        }
        self.evaluations += (STAGES - 1) as u64;
        combine(&mut self.y_new, &self.y, h, &B, &self.k);
        Ok(())
    }

    /// Hairer's error measure of the candidate step (`<= 1`: accept).
    fn error_norm(&self, h: f64) -> f64 {
        let n = self.dim;
        let Tolerances { rtol, atol, .. } = self.tolerances;
        let (mut err5, mut err3) = (0.0, 0.0);
        for i in 0..n {
            let sk = atol + rtol * self.y[i].abs().max(self.y_new[i].abs());
            let (mut e5, mut e3) = (0.0, 0.0);
            for j in 0..STAGES {
                let kj = self.k[j * n + i];
                e5 += E5[j] * kj;
                e3 += E3[j] * kj;
            }
            err5 += (e5 / sk) * (e5 / sk);
            err3 += (e3 / sk) * (e3 / sk);
        }
        let mut deno = err5 + 0.01 * err3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * err5 * (1.0 / (n as f64 * deno)).sqrt()
    }

    /// Writes the dense output of the last accepted step at `tau` into `out`, computing its
    /// coefficients first if this step has not given a sample yet.
    fn interpolate<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        tau: f64,
        out: &mut [f64],
    ) -> Result<()> {
        if !self.dense_ready {
            self.dense_coefficients(f)?;
        }
        let n = self.dim;
        let s = (tau - self.t_old) / self.h_old;
        let s1 = 1.0 - s;
        let r = |m: usize, i: usize| self.dense[(m - 2) * n + i];
        for (i, o) in out.iter_mut().enumerate() {
            let par = r(5, i) + s * (r(6, i) + s1 * (r(7, i) + s * r(8, i)));
            *o = self.y_old[i] + s * (r(2, i) + s1 * (r(3, i) + s * (r(4, i) + s1 * par)));
        }
        Ok(())
    }

    /// `r2 .. r8` of the last accepted step (three more evaluations: slots 13..15).
    fn dense_coefficients<F: VectorField + ?Sized>(&mut self, f: &F) -> Result<()> {
        let n = self.dim;
        let h = self.h_old;
        for s in STAGES + 1..SLOTS {
            combine(&mut self.stage, &self.y_old, h, &A[s][..s], &self.k);
            f.eval(
                self.t_old + C[s] * h,
                &self.stage,
                &mut self.k[s * n..(s + 1) * n],
            )?;
        }
        self.evaluations += (SLOTS - STAGES - 1) as u64;
        let (k1, f_new) = (&self.k[..n], &self.k[STAGES * n..(STAGES + 1) * n]);
        let (r234, r5678) = self.dense.split_at_mut(3 * n);
        for i in 0..n {
            let ydiff = self.y[i] - self.y_old[i];
            let bspl = h * k1[i] - ydiff;
            r234[i] = ydiff;
            r234[n + i] = bspl;
            r234[2 * n + i] = ydiff - h * f_new[i] - bspl;
        }
        for (m, row) in D.iter().enumerate() {
            let r = &mut r5678[m * n..(m + 1) * n];
            for (i, ri) in r.iter_mut().enumerate() {
                let mut acc = 0.0;
                for (j, d) in row.iter().enumerate() {
                    acc += d * self.k[j * n + i];
                }
                *ri = h * acc;
            }
        }
        self.dense_ready = true;
        Ok(())
    }
}

/// `out = y + h Σ_j a_j k_j`, `k_j` the slots of `k` (of `out.len()` components each).
#[inline]
fn combine(out: &mut [f64], y: &[f64], h: f64, a: &[f64], k: &[f64]) {
    let n = out.len();
    for (i, (o, yi)) in out.iter_mut().zip(y).enumerate() {
        let mut acc = 0.0;
        for (j, aj) in a.iter().enumerate() {
            acc += aj * k[j * n + i];
        }
        *o = yi + h * acc;
    }
}

/// Whether two output times are the same up to rounding ([`SAME_TIME_ULPS`]).
fn same_time(a: f64, b: f64) -> bool {
    (a - b).abs() <= SAME_TIME_ULPS * f64::EPSILON * a.abs().max(b.abs())
}

impl FieldStepper for Dop853 {
    /// Default tolerances, no bound.
    fn new(dim: usize) -> Self {
        Dop853::new(dim, Tolerances::default(), None)
    }

    #[inline]
    fn step_field<F: VectorField + ?Sized>(
        &mut self,
        f: &F,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<()> {
        self.advance(f, t, y, h)
    }
}

impl AdaptiveStepper for Dop853 {
    /// Bounded by a finite `t_bound`; unbounded for `+inf` (a session's run, which has no end).
    fn adaptive(dim: usize, tolerances: Tolerances, t_bound: f64) -> Self {
        Dop853::new(dim, tolerances, t_bound.is_finite().then_some(t_bound))
    }
}

impl Report for Dop853 {
    /// `rhs_evaluations`, `accepted_steps`, `rejected_steps`.
    fn report(&self, extra: &mut BTreeMap<String, ExtraValue>) {
        for (name, value) in [
            ("rhs_evaluations", self.evaluations),
            ("accepted_steps", self.accepted),
            ("rejected_steps", self.rejected),
        ] {
            extra.insert(name.into(), ExtraValue::Scalar(value as f64));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Row sums of `A` equal the nodes `c_s` (each stage is consistent); `b` and the dense rows
    /// sum as a consistent method needs (`Σ b = 1`); both error weights sum to zero (they
    /// estimate a difference of two consistent solutions). Coefficients carry ~1e-16 relative
    /// rounding each and rows have terms up to 43, so 1e-13 absolute.
    #[test]
    fn tableau_is_consistent() {
        for s in 1..SLOTS {
            let sum: f64 = A[s][..s].iter().sum();
            assert!((sum - C[s]).abs() < 1e-13, "row {s}: {sum} vs {}", C[s]);
        }
        assert!((B.iter().sum::<f64>() - 1.0).abs() < 1e-13);
        assert!(E5.iter().sum::<f64>().abs() < 1e-13);
        assert!(E3.iter().sum::<f64>().abs() < 1e-13);
        // Order conditions Σ b c^(q-1) = 1/q, q = 1..8, of the 8th-order quadrature.
        for q in 1..=8 {
            let sum: f64 = (0..STAGES).map(|j| B[j] * C[j].powi(q - 1)).sum();
            assert!((sum - 1.0 / f64::from(q)).abs() < 1e-13, "q = {q}: {sum}");
        }
    }
}
