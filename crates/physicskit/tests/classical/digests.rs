//! Stored trajectory digests: the bits of every spec system's trajectory, per method and
//! sampling, must not change unless a commit says why.
//!
//! # Why digests
//!
//! Refactors of the machinery (a system catalogue, a method table, a shared implicit solve)
//! must leave every trajectory bit-identical. Tolerance tests cannot see a change in the last
//! bit; a digest can. Each case builds a system through its public constructor with fixed,
//! non-trivial parameters, integrates a few hundred to two thousand steps and hashes, with
//! FNV-1a 64 (Fowler, Noll & Vo; written here, no dependency) over the little-endian bytes of
//! `f64::to_bits`:
//!
//! ```text
//! (rows, columns) of y,  t[..],  y[..] (row-major),  energy[..] (or a marker if absent),
//! the system's clock and state after the run (what a second `integrate` continues from)
//! ```
//!
//! The result is compared with the table [`DIGESTS`], one entry per
//! `system/method/sampling` case. A method the system refuses is recorded as `refused`, so
//! which methods each system accepts is pinned down too.
//!
//! # Why the bits are reproducible
//!
//! Rust does not reassociate or contract floating-point arithmetic, and this workspace never
//! enables `fma`: the SSE2, AVX2 and AVX-512 clones of the vectorized kernels round
//! identically, and the trig-bound forces (swarm, sine-Gordon) use our own slice sine/cosine
//! (`core/trig.rs`), so every x86-64 machine gives the same bits (ARCHITECTURE.md, "Vectorized
//! trig"). Ensembles use fixed chunk boundaries, so the thread count does not matter either.
//! One caveat: scalar `f64::sin`, `cos`, `exp`, `atan`, `cosh`, `powf` (pendulum, double
//! pendulum and hoop energies, kink initial data, the Kepler power law, ...) go to the
//! platform's libm, so the digests also assume glibc's libm on x86-64. A mismatch on another
//! platform (or libm) is expected and is not a regression.
//!
//! # When a digest changes
//!
//! The test lists every changed case. If the change is intended, regenerate the table with
//!
//! ```text
//! PHYSICSKIT_PRINT_DIGESTS=1 cargo test -p physicskit --test classical digests -- --nocapture
//! ```
//!
//! paste the printed table over [`DIGESTS`], and say in the commit message which cases changed
//! and why the new bits are right.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use physicskit::classical::examples::{HarmonicOscillator, Pendulum};
use physicskit::classical::systems::{
    BeadOnRotatingHoop, CoupledOscillators, CoupledOscillatorsParams, DoublePendulum,
    DoublePendulumParams, EulerTop, EulerTopParams, FPUTChain, HarmonicChain, HeavySymmetricTop,
    HenonHeilesSystem, HoopParams, KeplerPerturbations, KeplerSystem, PendulumSwarm,
    ProjectileMotion, SineGordonChain, SymmetricTopParams, PARALLEL_MEMBERS,
};
use physicskit::classical::{
    DynamicalSystem, Error, HamiltonianSystem, IntegrateOptions, LagrangianSystem, Method,
    OdeSystem, Result, Sampling, SimulationResult,
};

/// Set (to anything) to print the table instead of checking it.
const PRINT_ENV: &str = "PHYSICSKIT_PRINT_DIGESTS";

/// The digest of a case whose method the system refuses with `Error::UnsupportedMethod`.
const REFUSED: &str = "refused";

/// Stored digests, generated on x86-64 Linux (glibc); a case changes only with a deliberate
/// change of a method's arithmetic, named in the commit that regenerates it (the history of
/// each change is in the git log of this file).
const DIGESTS: &[(&str, &str)] = &[
    ("coupled_oscillators/blanes_moan6/all", "refused"),
    ("coupled_oscillators/dop853/all", "f03eea310a7aa040"),
    (
        "coupled_oscillators/gauss_legendre4/all",
        "efaf23fa54011e59",
    ),
    (
        "coupled_oscillators/gauss_legendre6/all",
        "ddbf026501678fde",
    ),
    (
        "coupled_oscillators/implicit_midpoint/all",
        "dd9cf9f6389ac790",
    ),
    ("coupled_oscillators/kahan_li6/all", "refused"),
    ("coupled_oscillators/kahan_li8/all", "refused"),
    ("coupled_oscillators/rk4/all", "9a48373467ca1f9b"),
    ("coupled_oscillators/sofroniou_spaletta10/all", "refused"),
    ("coupled_oscillators/taylor/all", "ab266604cf343688"),
    ("coupled_oscillators/verlet/all", "refused"),
    ("coupled_oscillators/yoshida4/all", "refused"),
    ("coupled_oscillators/yoshida6/all", "refused"),
    ("double_pendulum/blanes_moan6/all", "refused"),
    ("double_pendulum/dop853/all", "1893e1a0020fe47e"),
    ("double_pendulum/gauss_legendre4/all", "047c310340682ce1"),
    ("double_pendulum/gauss_legendre6/all", "81a48ca9c9688fb4"),
    ("double_pendulum/implicit_midpoint/all", "302c276647837e0b"),
    ("double_pendulum/kahan_li6/all", "refused"),
    ("double_pendulum/kahan_li8/all", "refused"),
    ("double_pendulum/rk4/all", "4094566ec6235c65"),
    ("double_pendulum/sofroniou_spaletta10/all", "refused"),
    ("double_pendulum/taylor/all", "4c2dc638e8cb346f"),
    ("double_pendulum/verlet/all", "refused"),
    ("double_pendulum/yoshida4/all", "refused"),
    ("double_pendulum/yoshida6/all", "refused"),
    ("euler_top/blanes_moan6/all", "refused"),
    ("euler_top/dop853/all", "1c1a24787978b1ca"),
    ("euler_top/gauss_legendre4/all", "76e3ed20d327c43f"),
    ("euler_top/gauss_legendre6/all", "43f65a611a0ad7d1"),
    ("euler_top/implicit_midpoint/all", "ccd8b9bdf9c8b93b"),
    ("euler_top/kahan_li6/all", "refused"),
    ("euler_top/kahan_li8/all", "refused"),
    ("euler_top/rk4/all", "de1f25eab547b2f4"),
    ("euler_top/sofroniou_spaletta10/all", "refused"),
    ("euler_top/taylor/all", "refused"),
    ("euler_top/verlet/all", "refused"),
    ("euler_top/yoshida4/all", "refused"),
    ("euler_top/yoshida6/all", "refused"),
    ("fput_beta/blanes_moan6/all", "a1857ac208a8afe6"),
    ("fput_beta/dop853/all", "c89932d4782659fb"),
    ("fput_beta/gauss_legendre4/all", "7a3b102a1eac0192"),
    ("fput_beta/gauss_legendre6/all", "ccf4a9aaa021fdde"),
    ("fput_beta/implicit_midpoint/all", "5877d29851c7590e"),
    ("fput_beta/kahan_li6/all", "36784d47246622d8"),
    ("fput_beta/kahan_li8/all", "df635f330ac608dc"),
    ("fput_beta/rk4/all", "1bbe8fffe3e26271"),
    ("fput_beta/sofroniou_spaletta10/all", "10aef6233ba7af33"),
    ("fput_beta/taylor/all", "refused"),
    ("fput_beta/verlet/all", "0aa11a89b6981eef"),
    ("fput_beta/yoshida4/all", "eaf95c22525b4c22"),
    ("fput_beta/yoshida6/all", "a6d7d7823598312c"),
    ("harmonic_chain/blanes_moan6/all", "7f740acb41306576"),
    ("harmonic_chain/dop853/all", "4ab75be8250da230"),
    ("harmonic_chain/gauss_legendre4/all", "0fc438a5ee2b722e"),
    ("harmonic_chain/gauss_legendre6/all", "844c6179ca38fd6f"),
    ("harmonic_chain/implicit_midpoint/all", "707677cdad6e587d"),
    ("harmonic_chain/kahan_li6/all", "a4caa8ff6c48e1a5"),
    ("harmonic_chain/kahan_li8/all", "04e4ffece231df0b"),
    ("harmonic_chain/rk4/all", "07c0a0495ae7aa1f"),
    (
        "harmonic_chain/sofroniou_spaletta10/all",
        "92f6f02fb31993fd",
    ),
    ("harmonic_chain/taylor/all", "refused"),
    ("harmonic_chain/verlet/all", "5c04637fc1afffca"),
    ("harmonic_chain/yoshida4/all", "9da262600e601c17"),
    ("harmonic_chain/yoshida6/all", "7ce8b865296d4311"),
    ("harmonic_oscillator/blanes_moan6/all", "313b13be0f8c05fd"),
    ("harmonic_oscillator/dop853/all", "7c67aaa63fa8c81a"),
    (
        "harmonic_oscillator/gauss_legendre4/all",
        "1092200b13997c3a",
    ),
    (
        "harmonic_oscillator/gauss_legendre6/all",
        "a80530605e61b12e",
    ),
    (
        "harmonic_oscillator/implicit_midpoint/all",
        "7dcf7e0dffcc5ec0",
    ),
    ("harmonic_oscillator/kahan_li6/all", "25e044c35fdea787"),
    ("harmonic_oscillator/kahan_li8/all", "cc811d8de4aeafb6"),
    ("harmonic_oscillator/rk4/all", "89eca2efeb0088ab"),
    (
        "harmonic_oscillator/sofroniou_spaletta10/all",
        "5e36153f8b01428f",
    ),
    ("harmonic_oscillator/taylor/all", "refused"),
    ("harmonic_oscillator/verlet/all", "33e22be3d92e0338"),
    ("harmonic_oscillator/yoshida4/all", "8d73efc6a8d0e631"),
    ("harmonic_oscillator/yoshida6/all", "d7e2ca1b66e92237"),
    ("heavy_symmetric_top/blanes_moan6/all", "refused"),
    ("heavy_symmetric_top/dop853/all", "de9812b5360112fa"),
    (
        "heavy_symmetric_top/gauss_legendre4/all",
        "71e0dfba3380dba6",
    ),
    (
        "heavy_symmetric_top/gauss_legendre6/all",
        "e8001544407d65ce",
    ),
    (
        "heavy_symmetric_top/implicit_midpoint/all",
        "d0d1b27312c1c827",
    ),
    ("heavy_symmetric_top/kahan_li6/all", "refused"),
    ("heavy_symmetric_top/kahan_li8/all", "refused"),
    ("heavy_symmetric_top/rk4/all", "87389d8dcb56e12c"),
    ("heavy_symmetric_top/sofroniou_spaletta10/all", "refused"),
    ("heavy_symmetric_top/taylor/all", "9812c5178603d673"),
    ("heavy_symmetric_top/verlet/all", "refused"),
    ("heavy_symmetric_top/yoshida4/all", "refused"),
    ("heavy_symmetric_top/yoshida6/all", "refused"),
    ("henon_heiles/blanes_moan6/all", "9eaf01403792665a"),
    ("henon_heiles/dop853/all", "da90a0f7cb625de1"),
    ("henon_heiles/gauss_legendre4/all", "fd096c5ddff25bd8"),
    ("henon_heiles/gauss_legendre6/all", "0a9124e24ed4ef30"),
    ("henon_heiles/implicit_midpoint/all", "c207af959da9a556"),
    ("henon_heiles/kahan_li6/all", "87f2b5ef7507a1d6"),
    ("henon_heiles/kahan_li8/all", "aaa323d80a3f3d26"),
    ("henon_heiles/rk4/all", "cda586fa7e4f959b"),
    ("henon_heiles/sofroniou_spaletta10/all", "476750758bcf13b2"),
    ("henon_heiles/taylor/all", "0f5982b598d64a47"),
    ("henon_heiles/verlet/all", "6838f013967fb371"),
    ("henon_heiles/yoshida4/all", "0e6858050973b846"),
    ("henon_heiles/yoshida6/all", "0d2669658d996ee8"),
    ("hoop/blanes_moan6/all", "refused"),
    ("hoop/dop853/all", "7a072b852239df6f"),
    ("hoop/gauss_legendre4/all", "42fc38af594a5e03"),
    ("hoop/gauss_legendre6/all", "a2e9e061c7eb9d25"),
    ("hoop/implicit_midpoint/all", "82298cf45fd9ac9c"),
    ("hoop/kahan_li6/all", "refused"),
    ("hoop/kahan_li8/all", "refused"),
    ("hoop/rk4/all", "4eb18340384223ef"),
    ("hoop/sofroniou_spaletta10/all", "refused"),
    ("hoop/taylor/all", "5aa3775125e34166"),
    ("hoop/verlet/all", "refused"),
    ("hoop/yoshida4/all", "refused"),
    ("hoop/yoshida6/all", "refused"),
    ("kepler_elements/blanes_moan6/all", "3fb47dd64c4c218f"),
    ("kepler_elements/blanes_moan6/final", "a0b7e1e7d41d4eca"),
    ("kepler_elements/blanes_moan6/stride7", "3d89aefc662c3da3"),
    ("kepler_elements/dop853/all", "7d47bdd93715d74b"),
    ("kepler_elements/dop853/final", "6d058a697b9cde2c"),
    ("kepler_elements/dop853/stride7", "0fc708d1a8066b4d"),
    ("kepler_elements/gauss_legendre4/all", "1de19d471204c8d6"),
    ("kepler_elements/gauss_legendre4/final", "8aa79088d4cb3a9d"),
    (
        "kepler_elements/gauss_legendre4/stride7",
        "47a05ed61351a82d",
    ),
    ("kepler_elements/gauss_legendre6/all", "e6540604cc9e8430"),
    ("kepler_elements/gauss_legendre6/final", "b3953efa7705a59d"),
    (
        "kepler_elements/gauss_legendre6/stride7",
        "f8b998e69e381865",
    ),
    ("kepler_elements/implicit_midpoint/all", "fa7d98d854979af2"),
    (
        "kepler_elements/implicit_midpoint/final",
        "1e55ac30be3f045f",
    ),
    (
        "kepler_elements/implicit_midpoint/stride7",
        "03651423c4c5c4ff",
    ),
    ("kepler_elements/kahan_li6/all", "b7726fb3b328c468"),
    ("kepler_elements/kahan_li6/final", "6b8915f6ba07150f"),
    ("kepler_elements/kahan_li6/stride7", "bbada7a116bd677a"),
    ("kepler_elements/kahan_li8/all", "1b7e682f18d97562"),
    ("kepler_elements/kahan_li8/final", "b5f97ae4cfe1b182"),
    ("kepler_elements/kahan_li8/stride7", "6478b7b82616576c"),
    ("kepler_elements/rk4/all", "119a64504cc50eb2"),
    ("kepler_elements/rk4/final", "ab8c384e3c643c2b"),
    ("kepler_elements/rk4/stride7", "4a36492288759cd6"),
    (
        "kepler_elements/sofroniou_spaletta10/all",
        "941a731d9e8e6fe1",
    ),
    (
        "kepler_elements/sofroniou_spaletta10/final",
        "cd94b6c939dc1b2c",
    ),
    (
        "kepler_elements/sofroniou_spaletta10/stride7",
        "f7467c700e987211",
    ),
    ("kepler_elements/taylor/all", "bbd1f1cb8a53c3ea"),
    ("kepler_elements/taylor/final", "240f453b468c8034"),
    ("kepler_elements/taylor/stride7", "17aa89f948c355fe"),
    ("kepler_elements/verlet/all", "9541c57e193eab69"),
    ("kepler_elements/verlet/final", "3ac30e2d347e490d"),
    ("kepler_elements/verlet/stride7", "028d7644b5be40f6"),
    ("kepler_elements/yoshida4/all", "48cb16c3e33d7716"),
    ("kepler_elements/yoshida4/final", "d53141c4a83d184f"),
    ("kepler_elements/yoshida4/stride7", "a90e59bf05ee4127"),
    ("kepler_elements/yoshida6/all", "6448f81d2fbd990b"),
    ("kepler_elements/yoshida6/final", "ab53f5c466ceb67c"),
    ("kepler_elements/yoshida6/stride7", "7c03a364feeb5fc3"),
    ("kepler_new/blanes_moan6/all", "4b285a4f939d3763"),
    ("kepler_new/dop853/all", "e607f0f2a6ba0ee2"),
    ("kepler_new/gauss_legendre4/all", "12925515e3bcac1c"),
    ("kepler_new/gauss_legendre6/all", "5b1f6595b14153b6"),
    ("kepler_new/implicit_midpoint/all", "400efcd0865974eb"),
    ("kepler_new/kahan_li6/all", "3b2a3af894f26e20"),
    ("kepler_new/kahan_li8/all", "711d10fb0d53b345"),
    ("kepler_new/rk4/all", "dd1325b5ced061fe"),
    ("kepler_new/sofroniou_spaletta10/all", "6d97bd4ff13c6532"),
    ("kepler_new/taylor/all", "ab114e6c06fcf114"),
    ("kepler_new/verlet/all", "90cd38210ec2b8b3"),
    ("kepler_new/yoshida4/all", "7d6dab72e0356672"),
    ("kepler_new/yoshida6/all", "d34b41ce3ae1650f"),
    ("kepler_pn_softened/blanes_moan6/all", "9da2186b18732dd3"),
    ("kepler_pn_softened/dop853/all", "b8b880f734950903"),
    ("kepler_pn_softened/gauss_legendre4/all", "bf3f9cf158695509"),
    ("kepler_pn_softened/gauss_legendre6/all", "853635077e247f44"),
    (
        "kepler_pn_softened/implicit_midpoint/all",
        "978d9a5b47e11f82",
    ),
    ("kepler_pn_softened/kahan_li6/all", "c801936294c2849f"),
    ("kepler_pn_softened/kahan_li8/all", "1e298398ae47c27a"),
    ("kepler_pn_softened/rk4/all", "6270431c2b6f5193"),
    (
        "kepler_pn_softened/sofroniou_spaletta10/all",
        "338d7304ff643d6d",
    ),
    ("kepler_pn_softened/taylor/all", "217e445981745847"),
    ("kepler_pn_softened/verlet/all", "d9430725af71e84f"),
    ("kepler_pn_softened/yoshida4/all", "9234953b02fe8a60"),
    ("kepler_pn_softened/yoshida6/all", "bbd745db2104e314"),
    ("kepler_power_law/blanes_moan6/all", "688668ae4533561d"),
    ("kepler_power_law/dop853/all", "f44fbc1df3e79f8c"),
    ("kepler_power_law/gauss_legendre4/all", "dfee6f6101d81edb"),
    ("kepler_power_law/gauss_legendre6/all", "77aa199b199408d6"),
    ("kepler_power_law/implicit_midpoint/all", "21515690e136b0bd"),
    ("kepler_power_law/kahan_li6/all", "d9fa62cc8646e3c2"),
    ("kepler_power_law/kahan_li8/all", "9210549133b51cc2"),
    ("kepler_power_law/rk4/all", "22973ccac9dba27f"),
    (
        "kepler_power_law/sofroniou_spaletta10/all",
        "3c6b6e183581630a",
    ),
    ("kepler_power_law/taylor/all", "08f3c9ccfe55fa5b"),
    ("kepler_power_law/verlet/all", "9e6c23682a3c3aea"),
    ("kepler_power_law/yoshida4/all", "f64f749aa5ca6c5b"),
    ("kepler_power_law/yoshida6/all", "ff3fda88981eef8d"),
    ("pendulum/blanes_moan6/all", "3d882d01f25dbefc"),
    ("pendulum/dop853/all", "42712aed04134f6f"),
    ("pendulum/gauss_legendre4/all", "e0aa282edaf0ae15"),
    ("pendulum/gauss_legendre6/all", "a93c8bdd5f290620"),
    ("pendulum/implicit_midpoint/all", "d1dd5f8263891852"),
    ("pendulum/kahan_li6/all", "f49f01c9bc2af9a5"),
    ("pendulum/kahan_li8/all", "0ac370c1a1e66e83"),
    ("pendulum/rk4/all", "a81ff6c7b7b1b06e"),
    ("pendulum/sofroniou_spaletta10/all", "d1c0b59d9f7a5931"),
    ("pendulum/taylor/all", "refused"),
    ("pendulum/verlet/all", "8755dbecbc17de4b"),
    ("pendulum/yoshida4/all", "69ec6b36d94b11bd"),
    ("pendulum/yoshida6/all", "f955349f0e823e9a"),
    ("projectile/blanes_moan6/all", "3961c723d8eefe78"),
    ("projectile/dop853/all", "7061f2eeedcc55ff"),
    ("projectile/gauss_legendre4/all", "59894e88450d858a"),
    ("projectile/gauss_legendre6/all", "4c8e6873d225cc07"),
    ("projectile/implicit_midpoint/all", "4c8e6873d225cc07"),
    ("projectile/kahan_li6/all", "0a77ae93b1ba268c"),
    ("projectile/kahan_li8/all", "a65ce68218a03048"),
    ("projectile/rk4/all", "eabc948b950e1b10"),
    ("projectile/sofroniou_spaletta10/all", "a6e0b1d34a4b0f1c"),
    ("projectile/taylor/all", "refused"),
    ("projectile/verlet/all", "09acb63483204538"),
    ("projectile/yoshida4/all", "20c608d9486834d9"),
    ("projectile/yoshida6/all", "af7329a0c3d31183"),
    ("projectile_drag/blanes_moan6/all", "refused"),
    ("projectile_drag/dop853/all", "8ad435fef787e223"),
    ("projectile_drag/gauss_legendre4/all", "8bd02e4ecb980166"),
    ("projectile_drag/gauss_legendre6/all", "ade0ca4ae2be85de"),
    ("projectile_drag/implicit_midpoint/all", "eafaf8369a74af36"),
    ("projectile_drag/kahan_li6/all", "refused"),
    ("projectile_drag/kahan_li8/all", "refused"),
    ("projectile_drag/rk4/all", "b2d693066d678180"),
    ("projectile_drag/sofroniou_spaletta10/all", "refused"),
    ("projectile_drag/taylor/all", "refused"),
    ("projectile_drag/verlet/all", "refused"),
    ("projectile_drag/yoshida4/all", "refused"),
    ("projectile_drag/yoshida6/all", "refused"),
    ("sine_gordon_kink/blanes_moan6/all", "9e0bc9da9014f62e"),
    ("sine_gordon_kink/dop853/all", "8cbb03df290614b8"),
    ("sine_gordon_kink/gauss_legendre4/all", "2b6d60e94266c1ce"),
    ("sine_gordon_kink/gauss_legendre6/all", "1a460b49581b0f4c"),
    ("sine_gordon_kink/implicit_midpoint/all", "5e4d1157426e5ab5"),
    ("sine_gordon_kink/kahan_li6/all", "975c059ee510c998"),
    ("sine_gordon_kink/kahan_li8/all", "9f76499a31b67fe3"),
    ("sine_gordon_kink/rk4/all", "ef370076a69a68ec"),
    (
        "sine_gordon_kink/sofroniou_spaletta10/all",
        "4a8cda4b9f02d8f4",
    ),
    ("sine_gordon_kink/taylor/all", "refused"),
    ("sine_gordon_kink/verlet/all", "ebc073581632a0a8"),
    ("sine_gordon_kink/yoshida4/all", "be4ee32a6af18ac6"),
    ("sine_gordon_kink/yoshida6/all", "887b2d1af3a3e468"),
    ("swarm_box/blanes_moan6/all", "0557e692da7a8ce4"),
    ("swarm_box/dop853/all", "75803b444f004771"),
    ("swarm_box/gauss_legendre4/all", "bc9144c6341407ea"),
    ("swarm_box/gauss_legendre6/all", "2235afc930743e04"),
    ("swarm_box/implicit_midpoint/all", "25e13a117badc77b"),
    ("swarm_box/kahan_li6/all", "9a67bf71bd9df711"),
    ("swarm_box/kahan_li8/all", "ca3d16ae8cdbae6c"),
    ("swarm_box/rk4/all", "044e1f8907cbc7de"),
    ("swarm_box/sofroniou_spaletta10/all", "225b792c99bee8d4"),
    ("swarm_box/taylor/all", "refused"),
    ("swarm_box/verlet/all", "0c86ea4e2d5711cc"),
    ("swarm_box/yoshida4/all", "8f8e90cbb105078e"),
    ("swarm_box/yoshida6/all", "3effc7725ca421bb"),
    ("swarm_new/blanes_moan6/all", "41f8fd5e5770d2cc"),
    ("swarm_new/dop853/all", "6f06cccf31f86fe3"),
    ("swarm_new/gauss_legendre4/all", "a60bfe7a304afde8"),
    ("swarm_new/gauss_legendre6/all", "43e7977e631cd008"),
    ("swarm_new/implicit_midpoint/all", "587de0ad0eb0de94"),
    ("swarm_new/kahan_li6/all", "9e67347d7feeb17c"),
    ("swarm_new/kahan_li8/all", "83c88b6eb0069c9d"),
    ("swarm_new/rk4/all", "2c69eaef741684cc"),
    ("swarm_new/sofroniou_spaletta10/all", "85538dc9cab43e09"),
    ("swarm_new/taylor/all", "refused"),
    ("swarm_new/verlet/all", "dfd5796ab6aa0ee8"),
    ("swarm_new/yoshida4/all", "f2d3e853559de1da"),
    ("swarm_new/yoshida6/all", "05bff08810601c3b"),
    ("swarm_parallel/blanes_moan6/all", "bd50799d3bde296f"),
    ("swarm_parallel/blanes_moan6/final", "8c6d5971355bf527"),
    ("swarm_parallel/dop853/all", "ae59436338f02ebe"),
    ("swarm_parallel/dop853/final", "4322916c6a48250f"),
    ("swarm_parallel/gauss_legendre4/all", "6d44b454cdf5b718"),
    ("swarm_parallel/gauss_legendre4/final", "ac737f281dd3f3f2"),
    ("swarm_parallel/gauss_legendre6/all", "20924fa2a41b5716"),
    ("swarm_parallel/gauss_legendre6/final", "af6a16fb122db8b3"),
    ("swarm_parallel/implicit_midpoint/all", "5b973b3068d647f7"),
    ("swarm_parallel/implicit_midpoint/final", "5458cde9505fe5d6"),
    ("swarm_parallel/kahan_li6/all", "ab1b373f70de116f"),
    ("swarm_parallel/kahan_li6/final", "611a3191e508e577"),
    ("swarm_parallel/kahan_li8/all", "2d7e6f985c9d3baa"),
    ("swarm_parallel/kahan_li8/final", "cad4b66a008a9b17"),
    ("swarm_parallel/rk4/all", "771e122ee02fa2bc"),
    ("swarm_parallel/rk4/final", "c4a9d7f75e677319"),
    (
        "swarm_parallel/sofroniou_spaletta10/all",
        "cee9dace6c9be9df",
    ),
    (
        "swarm_parallel/sofroniou_spaletta10/final",
        "8fc03d8f29c85d37",
    ),
    ("swarm_parallel/taylor/all", "refused"),
    ("swarm_parallel/taylor/final", "refused"),
    ("swarm_parallel/verlet/all", "e080c80da8de8fa1"),
    ("swarm_parallel/verlet/final", "d79611844de21bec"),
    ("swarm_parallel/yoshida4/all", "7903a520c2ca203c"),
    ("swarm_parallel/yoshida4/final", "2b2230e078a3fbed"),
    ("swarm_parallel/yoshida6/all", "d91a90a6cd41f469"),
    ("swarm_parallel/yoshida6/final", "0f8471cc65fcb2d7"),
];

/// FNV-1a, 64-bit: `h = (h ^ byte) * 0x100000001b3` from `h = 0xcbf29ce484222325`.
struct Fnv1a(u64);

impl Fnv1a {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    fn new() -> Self {
        Self(Self::OFFSET_BASIS)
    }

    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(Self::PRIME);
        }
    }

    fn u64(&mut self, x: u64) {
        self.bytes(&x.to_le_bytes());
    }

    fn f64s<'a>(&mut self, xs: impl IntoIterator<Item = &'a f64>) {
        for x in xs {
            self.u64(x.to_bits());
        }
    }
}

/// The digest of a finished run: the stored samples and the state the system was left in.
fn digest(result: &SimulationResult, system: &impl DynamicalSystem) -> String {
    let mut h = Fnv1a::new();
    let (rows, cols) = result.y.dim();
    h.u64(rows as u64);
    h.u64(cols as u64);
    h.f64s(&result.t);
    // `iter` walks the logical (row-major) order whatever the memory layout.
    h.f64s(&result.y);
    match &result.energy {
        Some(energy) => {
            h.u64(1);
            h.f64s(energy);
        }
        None => h.u64(0),
    }
    h.f64s(&[system.t()]);
    h.f64s(system.state());
    format!("{:016x}", h.0)
}

/// One way to call each family's `integrate`, so one loop serves every system.
/// `Sampling::All` goes through `integrate` itself (the call users make), the others through
/// `integrate_with`.
trait Run: DynamicalSystem + Sized {
    fn run(
        &mut self,
        t_span: (f64, f64),
        dt: f64,
        method: Method,
        sampling: Sampling,
    ) -> Result<SimulationResult>;
}

macro_rules! impl_run {
    ($family:ident: $($system:ty),+ $(,)?) => {$(
        impl Run for $system {
            fn run(
                &mut self,
                t_span: (f64, f64),
                dt: f64,
                method: Method,
                sampling: Sampling,
            ) -> Result<SimulationResult> {
                match sampling {
                    Sampling::All => $family::integrate(self, t_span, dt, method),
                    _ => $family::integrate_with(
                        self,
                        t_span,
                        dt,
                        method,
                        IntegrateOptions {
                            sampling,
                            ..IntegrateOptions::default()
                        },
                    ),
                }
            }
        }
    )+};
}

impl_run!(HamiltonianSystem: KeplerSystem, HenonHeilesSystem, PendulumSwarm, ProjectileMotion,
    HarmonicChain, FPUTChain, SineGordonChain, Pendulum, HarmonicOscillator);
impl_run!(LagrangianSystem: DoublePendulum, BeadOnRotatingHoop, CoupledOscillators,
    HeavySymmetricTop);
impl_run!(OdeSystem: EulerTop);

/// The digests computed in this run, by case name.
#[derive(Default)]
struct Cases(BTreeMap<String, String>);

impl Cases {
    /// Runs a fresh system from `make` with every method of [`Method::ALL`] and records one
    /// digest per method as `name/method/sampling`.
    fn every_method<S: Run>(
        &mut self,
        name: &str,
        make: impl Fn() -> Result<S>,
        t_span: (f64, f64),
        dt: f64,
        sampling: Sampling,
    ) {
        let label = match sampling {
            Sampling::All => "all".to_string(),
            Sampling::Stride(k) => format!("stride{k}"),
            Sampling::FinalOnly => "final".to_string(),
        };
        for method in Method::ALL {
            let case = format!("{name}/{method}/{label}");
            let mut system = make().unwrap_or_else(|e| panic!("{case}: constructor failed: {e}"));
            let digest = match system.run(t_span, dt, method, sampling) {
                Ok(result) => {
                    assert_eq!(result.method, method.name(), "{case}");
                    digest(&result, &system)
                }
                Err(Error::UnsupportedMethod { .. }) => REFUSED.to_string(),
                Err(e) => panic!("{case}: integration failed: {e}"),
            };
            assert!(
                self.0.insert(case.clone(), digest).is_none(),
                "duplicate case {case}"
            );
        }
    }
}

/// Every case: the 12 spec systems and the two examples, every method, full sampling; a
/// stride and a final-only run of one Kepler orbit; the swarm's parallel ensemble path.
fn compute_cases() -> Cases {
    let mut c = Cases::default();
    let all = Sampling::All;

    // Kepler: eccentric orbits, so the force varies strongly over the run.
    c.every_method(
        "kepler_new",
        || {
            KeplerSystem::new(
                &[1.0, 0.1],
                &[-0.05, 1.1],
                1.0,
                1.0,
                KeplerPerturbations::none(),
            )
        },
        (0.0, 5.0),
        1e-2,
        all,
    );
    let elements =
        || KeplerSystem::from_orbital_elements(1.3, 0.6, 1.0, 0.8, KeplerPerturbations::none());
    c.every_method("kepler_elements", elements, (0.0, 5.0), 5e-3, all);
    // 1000 steps: stride 7 leaves a remainder, so the extra final sample is covered too.
    c.every_method(
        "kepler_elements",
        elements,
        (0.0, 5.0),
        5e-3,
        Sampling::Stride(7),
    );
    c.every_method(
        "kepler_elements",
        elements,
        (0.0, 5.0),
        5e-3,
        Sampling::FinalOnly,
    );
    c.every_method(
        "kepler_pn_softened",
        || {
            let pert = KeplerPerturbations::none()
                .with_post_newtonian(1e-3)
                .with_softening(0.05);
            KeplerSystem::new(&[0.9, -0.2], &[0.1, 1.05], 1.0, 1.0, pert)
        },
        (0.0, 5.0),
        1e-2,
        all,
    );
    c.every_method(
        "kepler_power_law",
        || {
            let pert = KeplerPerturbations::none().with_power_law(0.1, 0.02);
            KeplerSystem::new(&[0.9, -0.2], &[0.1, 1.05], 1.0, 1.0, pert)
        },
        (0.0, 5.0),
        1e-2,
        all,
    );

    // Hénon–Heiles at E ~ 0.092 (below the escape energy 1/6).
    c.every_method(
        "henon_heiles",
        || HenonHeilesSystem::new(&[0.1, -0.2], &[0.35, 0.1]),
        (0.0, 10.0),
        1e-2,
        all,
    );

    // Swarms: a hand-written one and a seeded box of 100 (past the 64-coordinate threshold of
    // the vectorized kick and drift).
    c.every_method(
        "swarm_new",
        || {
            PendulumSwarm::new(
                &[0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0],
                &[0.0, 0.3, -0.2, 0.5, -0.4, 0.1, 0.05],
                2.5,
            )
        },
        (0.0, 5.0),
        1e-2,
        all,
    );
    c.every_method(
        "swarm_box",
        || PendulumSwarm::from_box(1.0, 0.2, 0.5, 0.3, 100, 1.5, 42),
        (0.0, 5.0),
        1e-2,
        all,
    );
    // PARALLEL_MEMBERS pendulums go through the parallel ensemble; 4 steps keep it cheap.
    let big = || PendulumSwarm::from_box(0.0, 0.0, 2.0, 1.0, PARALLEL_MEMBERS, 1.0, 7);
    c.every_method("swarm_parallel", big, (0.0, 0.04), 1e-2, all);
    c.every_method(
        "swarm_parallel",
        big,
        (0.0, 0.04),
        1e-2,
        Sampling::FinalOnly,
    );

    c.every_method(
        "projectile",
        || ProjectileMotion::new(&[0.0, 1.0], &[3.0, 4.0], 0.5, 9.81, 0.0),
        (0.25, 1.05),
        1e-3,
        all,
    );
    c.every_method(
        "projectile_drag",
        || ProjectileMotion::new(&[0.0, 1.0], &[3.0, 4.0], 0.5, 9.81, 0.1),
        (0.25, 1.05),
        1e-3,
        all,
    );

    // Chains.
    c.every_method(
        "harmonic_chain",
        || {
            HarmonicChain::new(
                &[0.3, -0.1, 0.2, 0.0, 0.5, -0.4, 0.1, 0.2],
                &[0.0, 0.4, -0.2, 0.1, 0.0, 0.3, -0.1, 0.05],
                1.3,
                0.7,
            )
        },
        (0.0, 10.0),
        1e-2,
        all,
    );
    c.every_method(
        "fput_beta",
        || FPUTChain::new(32, 1.0, 1.0, 1.5, 1, 1.0),
        (0.0, 50.0),
        5e-2,
        all,
    );
    // A boosted kink on m = k = 9 (width 3, a genuine soliton), 80 sites.
    c.every_method(
        "sine_gordon_kink",
        || {
            let (m, k) = (9.0, 9.0);
            let (q0, p0) = SineGordonChain::kink(80, 30.0, 3.0, 0.3, 1)?;
            let p0: Vec<f64> = p0.iter().map(|p| m * p).collect();
            SineGordonChain::new(80, m, k, Some(&q0), Some(&p0))
        },
        (0.0, 30.0),
        5e-2,
        all,
    );

    // Lagrangian systems.
    c.every_method(
        "double_pendulum",
        || {
            let params = DoublePendulumParams {
                m1: 1.0,
                m2: 0.7,
                l1: 1.1,
                l2: 0.8,
                g: 9.81,
            };
            DoublePendulum::new(&[1.2, -0.5], &[0.3, 1.0], params)
        },
        (0.0, 1.0),
        1e-3,
        all,
    );
    c.every_method(
        "hoop",
        || {
            let params = HoopParams {
                r: 0.8,
                omega: 5.0,
                g: 9.81,
            };
            BeadOnRotatingHoop::new(0.9, 0.4, params)
        },
        (0.0, 1.0),
        1e-3,
        all,
    );
    c.every_method(
        "coupled_oscillators",
        || {
            let params = CoupledOscillatorsParams {
                n: 4,
                m: 1.2,
                k: 0.9,
            };
            CoupledOscillators::new(&[0.3, -0.1, 0.2, 0.0], &[0.0, 0.4, -0.2, 0.1], params)
        },
        (0.0, 5.0),
        1e-2,
        all,
    );
    c.every_method(
        "heavy_symmetric_top",
        || {
            let params = SymmetricTopParams {
                i1: 1.2,
                i3: 0.4,
                m: 0.9,
                l: 1.1,
                g: 9.81,
            };
            HeavySymmetricTop::new(&[0.1, 0.8, 0.0], &[0.5, 0.0, 12.0], params)
        },
        (0.0, 1.0),
        1e-3,
        all,
    );

    c.every_method(
        "euler_top",
        || {
            let params = EulerTopParams {
                i1: 1.2,
                i2: 2.1,
                i3: 3.3,
            };
            EulerTop::new(&[0.3, 1.0, -0.4], params, Some(&[0.9, 0.1, -0.3, 0.2]))
        },
        (0.25, 1.25),
        1e-3,
        all,
    );

    // The examples.
    c.every_method(
        "pendulum",
        || Pendulum::new(2.0, 0.3, 4.0),
        (0.25, 10.25),
        1e-2,
        all,
    );
    c.every_method(
        "harmonic_oscillator",
        || HarmonicOscillator::new(1.0, -0.5, 2.0, 3.0),
        (0.0, 10.0),
        1e-2,
        all,
    );
    c
}

#[test]
fn trajectories_match_the_stored_digests() {
    let computed = compute_cases().0;

    if std::env::var_os(PRINT_ENV).is_some() {
        let mut table = String::from("const DIGESTS: &[(&str, &str)] = &[\n");
        for (case, digest) in &computed {
            writeln!(table, "    (\"{case}\", \"{digest}\"),").unwrap();
        }
        table.push_str("];");
        println!("{table}");
        println!("{PRINT_ENV} is set: the table above was printed, not checked.");
        return;
    }

    let stored: BTreeMap<&str, &str> = DIGESTS.iter().copied().collect();
    assert_eq!(stored.len(), DIGESTS.len(), "duplicate case in DIGESTS");
    let mut problems = String::new();
    for (case, digest) in &computed {
        match stored.get(case.as_str()) {
            Some(s) if *s == digest => {}
            Some(s) => writeln!(problems, "  {case}: stored {s}, now {digest}").unwrap(),
            None => writeln!(problems, "  {case}: not in DIGESTS (now {digest})").unwrap(),
        }
    }
    for case in stored.keys() {
        if !computed.contains_key(*case) {
            writeln!(problems, "  {case}: in DIGESTS but no longer computed").unwrap();
        }
    }
    assert!(
        problems.is_empty(),
        "trajectories changed bits in these cases:\n{problems}\
         Existing trajectories must stay bit-identical. If the change is intended, regenerate \
         the table with `{PRINT_ENV}=1 cargo test -p physicskit --test classical digests -- \
         --nocapture`, paste it over DIGESTS in tests/classical/digests.rs, and justify in \
         the commit message which cases changed and why."
    );
}

#[test]
fn the_hash_is_fnv1a_64_and_sees_one_bit() {
    // Published FNV-1a 64 test vectors (Fowler, Noll & Vo, draft-eastlake-fnv): "" and "a".
    assert_eq!(Fnv1a::new().0, 0xcbf2_9ce4_8422_2325);
    let mut h = Fnv1a::new();
    h.bytes(b"a");
    assert_eq!(h.0, 0xaf63_dc4c_8601_ec8c);
    // A change in the last bit of one sample changes the digest.
    let mut p = Pendulum::new(2.0, 0.3, 4.0).unwrap();
    let mut result =
        HamiltonianSystem::integrate(&mut p, (0.0, 1.0), 1e-2, Method::Verlet).unwrap();
    let before = digest(&result, &p);
    result.y[[50, 1]] = f64::from_bits(result.y[[50, 1]].to_bits() ^ 1);
    assert_ne!(digest(&result, &p), before);
}
