//! The heavy symmetric top's symmetry axis against the z-x-z rotation built from elementary
//! rotations (Goldstein, *Classical Mechanics*, 3rd ed., §4.4).

use physicskit::classical::model::erased::Capabilities;
use physicskit::classical::systems::{HeavySymmetricTop, SymmetricTopParams};
use physicskit::classical::Error;

type Mat = [[f64; 3]; 3];

fn mul(a: &Mat, b: &Mat) -> Mat {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn rot_z(a: f64) -> Mat {
    let (s, c) = a.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn rot_x(a: f64) -> Mat {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

fn top(l: f64) -> HeavySymmetricTop {
    let params = SymmetricTopParams {
        l,
        ..SymmetricTopParams::default()
    };
    HeavySymmetricTop::new(&[0.3, 0.5, 0.0], &[0.0, 0.0, 20.0], params).unwrap()
}

#[test]
// The default q is the stored one: the same bits, an exact comparison.
#[allow(clippy::float_cmp)]
fn symmetry_axis_is_the_body_z_axis_of_the_z_x_z_rotation() {
    // Body to space: R = Rz(phi) Rx(theta) Rz(psi); the body z axis in space is R e3, its
    // third column. Products of order-1 factors in another order: a few ulps.
    let top = top(1.0);
    for (phi, theta, psi) in [(0.3, 0.5, 0.0), (-2.0, 2.9, 1.7), (4.0, 0.01, -3.0)] {
        let r = mul(&mul(&rot_z(phi), &rot_x(theta)), &rot_z(psi));
        let axis = top.symmetry_axis(Some(&[phi, theta, psi])).unwrap();
        for i in 0..3 {
            assert!((axis[i] - r[i][2]).abs() < 1e-15, "{axis:?} vs {r:?}");
        }
        let norm: f64 = axis.iter().map(|x| x * x).sum();
        assert!((norm - 1.0).abs() < 4e-16, "{norm}");
    }
    assert_eq!(
        top.symmetry_axis(None).unwrap(),
        top.symmetry_axis(Some(&[0.3, 0.5, 0.0])).unwrap()
    );
}

#[test]
fn centre_of_mass_lies_on_the_axis_at_distance_l() {
    // positions = l * axis, whatever the sign of l (a top hanging below its pivot has l < 0);
    // one product each, so equal to the bit.
    for l in [1.0, 0.37, -0.5] {
        let top = top(l);
        let q = [1.1, 0.8, -0.4];
        let axis = Capabilities::symmetry_axis(&top, &q).unwrap().unwrap();
        let pos = Capabilities::positions(&top, &q).unwrap().unwrap();
        assert_eq!(pos, axis.map(|x| l * x).to_vec());
    }
}

#[test]
fn symmetry_axis_of_the_wrong_length_is_an_error() {
    let top = top(1.0);
    assert!(matches!(
        top.symmetry_axis(Some(&[0.0, 0.5])),
        Err(Error::DimensionMismatch {
            expected: 3,
            found: 2,
            ..
        })
    ));
}
