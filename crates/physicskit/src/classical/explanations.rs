//! The physics explanations: one paragraph per gallery demonstration, keyed by the
//! demonstration's slug and mapped to the catalogue systems ([`catalog::SYSTEMS`] names) it
//! shows.
//!
//! This is the one source of those texts. The gallery (`physicskit-viz`) prints
//! [`for_demo`]`(slug)` under each demonstration; the catalogue JSON (`physicskit-listing`,
//! read by `physicskit list --json` and by the browser lab) carries [`for_system`]`(name)` as
//! each system's `physics` field, which the lab shows as the system's caption. A system no
//! demonstration shows (the harmonic oscillator) has none.
//!
//! Each paragraph is in two parts: the physics of the system or analysis, true for any
//! parameters, and what the gallery's figures show (their parameters, grid sizes, run times and
//! panels). The lab, which starts from the catalogue's defaults and lets the reader change
//! them, shows only the first part. Every demonstration has both parts, and the first states no
//! number the second does (`tests/classical/explanations.rs`).
//!
//! [`catalog::SYSTEMS`]: crate::classical::catalog::SYSTEMS

/// One demonstration's physics paragraph.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Explanation {
    /// The gallery demonstration's anchor name, e.g. `"double-pendulum"`.
    pub slug: &'static str,
    /// The catalogue systems the paragraph describes (each in at most one explanation); none
    /// for a demonstration about a method or an analysis across systems whose own paragraphs
    /// are elsewhere (work–precision, the flip-time fractal, the precession sweep, the chaos
    /// maps and the hoop's bifurcation diagram).
    pub systems: &'static [&'static str],
    /// The physics, true of the system or analysis whatever its parameters (plain text,
    /// Unicode): what the lab shows beside a run from any setting.
    pub text: &'static str,
    /// What the gallery's figures show: their parameters, grid sizes, run times and panels
    /// (never empty). The gallery prints it after [`text`](Self::text); the lab, which starts
    /// from the catalogue's defaults, does not.
    pub figure: &'static str,
}

/// The paragraph of the gallery demonstration `slug`, if there is one.
pub fn for_demo(slug: &str) -> Option<&'static Explanation> {
    EXPLANATIONS.iter().find(|e| e.slug == slug)
}

/// The paragraph describing the catalogue system `name`, if a demonstration shows it.
pub fn for_system(name: &str) -> Option<&'static str> {
    EXPLANATIONS
        .iter()
        .find(|e| e.systems.contains(&name))
        .map(|e| e.text)
}

/// Every explanation, in gallery order.
pub static EXPLANATIONS: &[Explanation] = &[
    Explanation {
        slug: "double-pendulum",
        systems: &["double-pendulum"],
        text:
            "Two rigid rods, each with a bob at its end, hanging from a fixed pivot. Given enough \
         energy the motion is deterministic yet chaotic: two runs whose starting angles \
         differ by a billionth of a radian separate exponentially (a straight rise of the log \
         of their separation, whose slope is the largest Lyapunov exponent) until the \
         difference is as large as the motion itself, and the lower bob's angle θ₂ against \
         its canonical momentum p₂ fills a region instead of tracing a closed curve. Its \
         Hamiltonian is not separable (the mass matrix depends on θ₁ − θ₂), so the symplectic \
         choices are the implicit methods (implicit midpoint, Gauss–Legendre): their energy \
         error stays bounded, while rk4's drifts.",
        figure:
            "Rods of 1 m with 1 kg bobs (g = 9.81 m/s²) released from 115° and 138°; the second \
         run starts 10⁻⁹ rad away; the integrators are the implicit midpoint rule and rk4.",
    },
    Explanation {
        slug: "henon-heiles",
        systems: &["henon-heiles"],
        text: "A star in an axisymmetric galaxy (Hénon & Heiles 1964), H = (px² + py²)/2 + (x² + \
         y²)/2 + x²y − y³/3. A Poincaré section records each crossing of the plane y = 0 with \
         py > 0 (located exactly with Hénon's trick, not taken from the nearest time step). \
         At low energy almost every orbit's crossings lie on a smooth closed curve, the \
         section of an invariant (KAM) torus: the motion is regular. As the energy rises, the \
         tori between the islands dissolve into a chaotic sea of scattered dots, and at E = \
         1/6, the energy of the saddle points of the potential, almost all tori are gone.",
        figure: "Each colour is one orbit; the three panels are at E = 1/12 (almost everything \
         regular), E = 1/8 (islands in a chaotic sea) and the saddles' energy.",
    },
    Explanation {
        slug: "swarm",
        systems: &["pendulum-swarm", "pendulum-swarm-state"],
        text: "A cloud of identical, independent pendulums starts as a small rectangle in phase \
         space (angle q, momentum p). Near the separatrix, the boundary between swinging and \
         whirling motion, the swing period depends strongly on the energy, so the patch is \
         sheared and wound into a long thin filament; yet by Liouville's theorem the \
         Hamiltonian flow preserves phase-space area, so the area enclosed by the patch's \
         boundary stays at its initial value.",
        figure:
            "g/l = 1 s⁻²; the patch starts just inside the separatrix, and its area is measured \
         on 2000 boundary points carried along with the flow.",
    },
    Explanation {
        slug: "fput",
        systems: &["fput"],
        text: "A chain of unit masses joined by springs with a weak quartic non-linearity (V(r) = \
         r²/2 + β r⁴/4, fixed ends) starts in its lowest normal mode. Fermi, Pasta, Ulam and \
         Tsingou expected the non-linearity to share the energy out evenly among all modes \
         (equipartition). Instead the energy flows into a few neighbouring modes and then \
         comes back almost entirely to mode 1: the FPUT recurrence, an early hint of solitons \
         and of KAM stability. (The quartic force keeps the chain's left–right symmetry, so \
         the even modes are never excited.)",
        figure: "32 masses; the figure follows the energies of the lowest modes.",
    },
    Explanation {
        slug: "sine-gordon",
        systems: &["sine-gordon", "sine-gordon-state"],
        text: "A chain of pendulums on a torsion spring (the Frenkel–Kontorova model) is the \
         lattice form of the sine-Gordon equation q_tt = c² q_xx − sin q. A kink is a \
         travelling twist by 2π in which the pendulums turn over one after another; an \
         antikink twists back. They behave like particles: sent towards each other, they \
         collide, pass through each other and re-emerge with their shapes intact, the \
         signature of a soliton (the lattice sheds only a little radiation).",
        figure: "The kink and the antikink approach each other at 0.4 of the wave speed.",
    },
    Explanation {
        slug: "chains",
        systems: &["harmonic-chain", "coupled-oscillators"],
        text: "Masses joined by identical springs between two walls move, for small oscillations, \
         as a superposition of normal modes: standing waves in which every mass oscillates at \
         the same frequency ωⱼ = 2√(k/m) sin(jπ/2(N+1)). Started in a mode shape, the chain \
         stays in it. Started in a superposition of two modes of close frequencies, each mode \
         keeps its own energy, yet a single mass swells and falls silent at the difference \
         frequency, cos(ω₁t) + cos(ω₂t) = 2 cos(Δω t/2) cos(ω̄ t): beats are interference.",
        figure:
            "The first figure shows the shapes of the four lowest modes of an 8-mass chain, each \
         checked by simulation (the dots are the displacements half a period later, flipped \
         in sign as a standing wave must be). The second shows beats in a 12-mass chain \
         started in a superposition of its two highest modes (ω₁₁ and ω₁₂).",
    },
    Explanation {
        slug: "kepler",
        systems: &["kepler", "kepler-state"],
        text:
            "A planet in an inverse-square force traces the same closed ellipse for ever: besides \
         energy and angular momentum, the Laplace–Runge–Lenz vector, which points at the \
         perihelion, is conserved, a symmetry special to 1/r². Adding a small attractive 1/r³ \
         term, the effective post-Newtonian correction of general relativity, breaks that \
         symmetry: the ellipse turns a little every orbit into a rosette, and the LRL \
         vector's angle grows at a steady rate, the perihelion precession (43 arc-seconds per \
         century for Mercury).",
        figure: "Units with G M = 1; semi-major axis 1, eccentricity 0.6.",
    },
    Explanation {
        slug: "euler-top",
        systems: &["euler-top"],
        text:
            "A free rigid body with three different principal moments I₁ < I₂ < I₃ rotates stably \
         about its smallest and its largest axis, but not about the intermediate one: spun \
         almost exactly about it, the spin ω₂ periodically reverses, the body flipping over \
         while angular momentum stays fixed in space (the effect the cosmonaut Dzhanibekov \
         saw with a wing nut). In the body frame the angular momentum L moves on a sphere |L| \
         = const along its intersections with the energy ellipsoid, the polhodes: closed \
         loops around the stable axes 1 and 3, and separatrices through the unstable axis 2. \
         The implicit midpoint rule keeps energy and |L| exactly, so the computed curves \
         close.",
        figure: "I₁ = 1, I₂ = 2, I₃ = 3 (a flat plate), spun almost exactly about axis 2.",
    },
    Explanation {
        slug: "heavy-top",
        systems: &["heavy-top"],
        text:
            "A spinning top with its tip fixed precesses slowly about the vertical while its axis \
         nods up and down (nutation). Because the angles φ and ψ do not appear in the \
         Lagrangian, their momenta are conserved and the tilt θ moves like a particle in the \
         effective potential V_eff(θ): it oscillates between the two turning points where \
         V_eff equals the energy, so θ against its rate is the revealing phase portrait. \
         Depending on the start, the tip of the axis draws waves, loops or, started from rest \
         in φ, cusps on the unit sphere.",
        figure:
            "I₁ = 1, I₃ = 0.5 kg m², M g l = 9.81 J, started with a small backward precession: \
         the tip draws loops.",
    },
    Explanation {
        slug: "hoop",
        systems: &["hoop"],
        text:
            "A bead slides without friction on a vertical hoop of radius R spun at a fixed rate ω \
         about its vertical diameter. In the rotating frame gravity pulls the bead down and \
         the centrifugal force pushes it out. Below the critical rate ω_c = √(g/R) the bottom \
         θ = 0 is the only stable rest point; above it the bottom becomes unstable and two \
         new stable equilibria appear at cos θ = g/(Rω²), climbing the hoop as ω grows: a \
         pitchfork bifurcation, the textbook example of spontaneous symmetry breaking. In \
         phase space the single centre turns into a saddle between two centres.",
        figure: "R = 1 m, g = 9.81 m/s², ω up to 2.5 ω_c; the phase portraits are at ω = 0.7 ω_c \
         and 1.6 ω_c.",
    },
    Explanation {
        slug: "projectile",
        systems: &["projectile", "projectile-state"],
        text: "Without air resistance every trajectory is Galileo's parabola and the range v² \
         sin(2θ)/g is largest at 45°, with complementary angles (30° and 60°) landing at the \
         same spot. Quadratic air drag (force −c|v|v) takes energy out of the flight: the \
         paths become lopsided, steeper on the way down, the range shrinks a lot, and the \
         best launch angle drops below 45°.",
        figure: "A 1 kg ball launched at 40 m/s; with drag its terminal speed is 22 m/s.",
    },
    Explanation {
        slug: "integrators",
        systems: &["pendulum"],
        text:
            "The symplectic methods (verlet, yoshida4 and the higher-order compositions) and the \
         implicit midpoint rule conserve a modified energy exactly, so their energy error \
         oscillates but never grows, however long the run; rk4 is more accurate per step than \
         verlet but not symplectic, and its energy error grows steadily. The order p of a \
         method shows in the slope of its error at a fixed time against the step size (error \
         ∝ dt^p): 2 for verlet and implicit_midpoint, 4 for yoshida4 and rk4.",
        figure:
            "The same pendulum (released from 115°, g/l = 1 s⁻²) integrated with the four methods \
         of the specification, and the convergence plot of their errors.",
    },
    Explanation {
        slug: "toda",
        systems: &["toda"],
        text: "Unit masses on a ring joined by exponential springs, V(r) = (a/b) e^(−b r) (stiff \
         under compression, soft under stretching), the lattice Morikazu Toda found in 1967. \
         A kick launches a compression pulse (a lattice soliton) that runs around the ring, \
         and the energy sloshes from particle to particle. Yet the motion is completely \
         integrable: Flaschka's Lax matrix L (diagonal pᵢ, off-diagonal √(a/b) e^(−b rᵢ/2), \
         corners closing the ring) only rotates as time goes on, so its eigenvalues are \
         conserved (the sum of their squares is twice the energy). The FPUT chain is the same \
         kind of lattice with a polynomial spring: it is only close to integrable, which is \
         why its energy nearly, but not exactly, returns.",
        figure: "Sixteen masses, a = b = 1; two particles are kicked with 3 and −1.5 units of \
         momentum. Left: the energy of each particle above its equilibrium share a/b; middle: \
         two particles; right: the sixteen eigenvalues of L, flat lines.",
    },
    Explanation {
        slug: "elastic-pendulum",
        systems: &["elastic-pendulum"],
        text:
            "A bob on a spring swings and bounces. Small bounces have the frequency ω_s = √(k/m), \
         small swings ω_p = √(g/r_eq), where r_eq = l0 + mg/k is the stretched length it \
         hangs at. When ω_s = 2ω_p the bob bounces twice per swing, rising at each end of the \
         swing and dropping at the bottom (as a child pumps a swing by standing and \
         crouching), and the energy passes almost completely from bounce to swing and back: \
         the Fermi resonance of the CO₂ molecule in a classroom toy. The condition is often \
         quoted as k/m = 4g/l0, but the swing sees the stretched length; solving k/m = \
         4g/r_eq gives k = 3mg/l0. The energies are split exactly: E − E_eq = [m ṙ²/2 + k(r − \
         r_eq)²/2] + [m r² θ̇²/2 + m g r (1 − cos θ)].",
        figure:
            "A 1 kg bob, rest length 1 m, g = 9.81 m/s², pulled 10 cm below its hanging position \
         and let go with a 1° swing: at the resonance, k = 29.43 N/m (r_eq = 4/3 m), the \
         energy passes to the swing; at k = 40 N/m (ω_s/ω_p = 2.25, close to the quoted rule) \
         the same start keeps bouncing with a swing that never grows.",
    },
    Explanation {
        slug: "flip-fractal",
        systems: &[],
        text: "Each pixel is one double pendulum released from rest at the angles (θ₁, θ₂); its \
         colour is the time until either arm first swings over the top (|θ| > π), located \
         inside the integration step. Energy alone forbids a flip where the energy at rest is \
         at or below the flip energy, that of the lowest state with an arm upside down (for \
         point bobs min(g₁ − |g₂|, g₂ − |g₁|), with g₁ = (m₁ + m₂) g l₁ and g₂ = m₂ g l₂: the \
         library's DoublePendulumParams::flip_energy). No member inside the black curve can \
         flip; those and the members that did not flip within the run are drawn at the top of \
         the scale. The boundaries between flip times are fractal (Heyl 2008): nearby starts \
         that straddle them flip at very different times, the fingerprint of chaos. Computed as \
         one ensemble on all cores (physicskit::classical::ensemble), bit-identical for any \
         number of threads.",
        figure: "Equal masses and arms (1 kg, 1 m, g = 9.81 m/s²), for which the curve is 2 cos \
         θ₁ + cos θ₂ = 1 (Heyl's 3 cos θ₁ + cos θ₂ = 2 is for uniform rods); 240 × 240 starts \
         run for 30 s with rk4 at dt = 0.01 s; times in units of √(l/g).",
    },
    Explanation {
        slug: "kepler-precession",
        systems: &[],
        text: "An ensemble of Kepler orbits with the post-Newtonian term c_pn/r³ added to the \
         potential −k/r, swept over a range of strengths. For each member the direction of the \
         Laplace–Runge–Lenz vector is followed along the run and its mean turning rate times \
         the orbital period gives the precession per orbit (dots). First-order perturbation \
         theory (Landau & Lifshitz §15) predicts Δφ = −6π c_pn μ² k / L⁴ per orbit (line): the \
         two agree for weak corrections and part at second order in c_pn.",
        figure: "Forty orbits of semi-major axis a = 1 and eccentricity e = 0.5 in units with μ = \
         k = 1, c_pn from −0.00025 to −0.01, each run for 20 periods with yoshida4 at 4000 \
         steps per period.",
    },
    Explanation {
        slug: "henon-heiles-regular-fraction",
        systems: &[],
        text: "How much of the Hénon–Heiles energy surface is regular, energy by energy. At \
         each energy E a grid of starts fills the surface of section x = 0 inside its \
         zero-velocity curve (p_x ≥ 0 from the energy); each start is one ensemble member whose \
         SALI (the smaller alignment index of two deviation vectors, Skokos 2001) is computed \
         on all cores. An orbit on an invariant torus keeps SALI away from zero; a chaotic one \
         drives it below the library's threshold of 10⁻⁸. The fraction of regular starts \
         estimates the relative area of the section covered by invariant curves, the quantity \
         Hénon & Heiles (1964) plotted against E: close to one up to about E = 0.11, then \
         falling steeply as the tori break up, with only small islands left near the escape \
         energy 1/6. A chaotic orbit that has not yet shown its chaos by the end of the run \
         counts as regular, so the curve is an upper estimate that longer runs lower.",
        figure: "Eleven energies from 1/24 to 0.16; at each, the cells of a 60 × 60 grid over the \
         energy curve's extent that lie inside it, each run to t = 3000 with yoshida4 at dt = \
         0.1.",
    },
    Explanation {
        slug: "work-precision",
        systems: &[],
        text: "How much accuracy each integrator buys per second of computing. Each line is one \
         method, each point one step size (halved from point to point) or, for the adaptive \
         dop853, one tolerance (tenfold apart); lower left is better. On the Kepler orbit (the \
         error is the phase lag after the run against the analytic orbit) and on Hénon–Heiles \
         (the largest energy error over the run), the high-order symplectic compositions \
         (kahan_li8, sofroniou_spaletta10) reach the rounding floor at a small fraction of the \
         cost of verlet or yoshida4, whose lines are steep but start far up. On the double \
         pendulum, a chaotic Lagrangian system where only the methods for non-separable systems \
         apply, the Gauss–Legendre methods of order 4 and 6 reach a given error far faster than \
         the second-order implicit midpoint rule. Wall times are of one run on a shared \
         machine: the slopes and the ordering matter, not the last digit.",
        figure: "Kepler at eccentricity e = 0.5 (a = k = μ = 1) over 100 orbits from perihelion; \
         SciML's Hénon–Heiles case, q = (0.1, 0) and p = (0, 0.5), to t = 1000; the double \
         pendulum with unit masses and arms from θ = (2, 1) rad and θ̇ = (0.5, −0.3) rad/s to t \
         = 10 s, against a dop853 reference run.",
    },
    Explanation {
        slug: "henon-heiles-sali",
        systems: &[],
        text: "The Hénon–Heiles system at one energy seen two ways on the same plane, the \
         section x = 0 with pₓ > 0 (pₓ fixed by the energy; the blank corners lie outside the \
         energy surface). Left, the Poincaré section: regular orbits draw closed curves, \
         sections of invariant tori, around the islands; chaotic ones scatter dots over a sea. \
         Right, every cell is one orbit started there, coloured by its Smaller Alignment Index \
         (Skokos 2001) at the end of the run: two deviation vectors follow the tangent dynamics \
         (the exact tangent map of the splitting step) and SALI measures how nearly they have \
         aligned. On a chaotic orbit both turn towards the most unstable direction and SALI \
         falls exponentially, as exp(−(λ₁ − λ₂)t); on a torus they stay apart and SALI stays of \
         order 0.1–1. Below the library's threshold of 10⁻⁸ (dark) an orbit is called chaotic; \
         the map draws the islands of the section in one run per cell, without following any \
         orbit by eye. Sticky orbits, which cling to an island's edge for a long time, have not \
         fallen below the threshold yet and show as intermediate colours.",
        figure: "E = 1/8; a 100 × 100 grid of starts run to t = 1000 with yoshida4 at dt = 0.05; \
         the section's 24 orbits cross the plane 800 times each.",
    },
    Explanation {
        slug: "double-pendulum-lyapunov",
        systems: &[],
        text: "Each pixel is one double pendulum released from rest at the angles (θ₁, θ₂), \
         coloured by its largest Lyapunov exponent: the growth rate, per second, of an \
         infinitesimal deviation carried by the tangent dynamics (Benettin's method, the \
         finite-time value at the end of the run). Inside the white curve the energy at rest is \
         at or below the flip energy, that of the lowest state with an arm upside down (the \
         library's DoublePendulumParams::flip_energy), so neither arm can ever flip: there the \
         map is dark, small exponents of mostly regular motion (a finite run leaves a residue \
         of order ln(t)/t even on a torus). Starts that the energy would let flip may still \
         stay on regular tori and extend the dark region beyond the curve. Further out the map \
         is a speckle of chaotic starts, the same structure the flip-time fractal shows in its \
         boundaries. The map has the pendulum's symmetry (θ₁, θ₂) → (−θ₁, −θ₂) up to the finite \
         run. Computed with the library's chaos map on all cores, bit-identical for any number \
         of threads.",
        figure: "Equal masses and arms (1 kg, 1 m, g = 9.81 m/s²), for which the curve is 2 cos \
         θ₁ + cos θ₂ = 1; 100 × 100 starts run to t = 20 s with rk4 at dt = 0.01 s, the \
         deviation renormalized every 10 steps. The dark region reaches beyond the curve in two \
         arms; the chaotic starts have exponents of one to two per second.",
    },
    Explanation {
        slug: "hoop-pitchfork",
        systems: &[],
        text: "The bead on the rotating hoop as a bifurcation diagram. Left: the equilibria at \
         rest against the rotation rate ω, from the library's analysis of V_eff = −R²ω² sin²θ/2 \
         + gR(1 − cos θ): the bottom is stable up to ω_c = √(g/R), then gives way to the pair \
         θ* = ±arccos(g/(Rω²)); the top is always unstable. Right: the largest Lyapunov \
         exponent at the bottom. Linearized about θ = 0 the motion is x'' = (ω² − g/R)x: a \
         centre below ω_c, with exponent zero, and a saddle above it, whose deviations grow as \
         exp(t√(ω² − g/R)) (line). The orbit resting exactly at the bottom has these tangent \
         dynamics, and its measured finite-time exponent follows the line, crossing zero at \
         ω_c; below ω_c it scatters about zero by the 1/t of a bounded rotation. An orbit \
         started slightly off the bottom is different: with one degree of freedom every orbit \
         lies on a regular curve, here a libration about one of the new minima that passes \
         close to the saddle. Over a short window near the saddle its deviations grow at the \
         saddle's rate, but over a long run they only grow linearly, and its exponent tends to \
         zero like ln(t)/t: the hoop is not chaotic, the exponent at the bottom measures the \
         instability of the equilibrium.",
        figure: "R = 1 m, g = 9.81 m/s², ω up to 2.5 ω_c; implicit midpoint at dt = 0.001 s; the \
         orbit at rest at the bottom (orange dots) run for 10 s, the one started 0.01 rad from \
         it (green dots) for 200 s.",
    },
];
