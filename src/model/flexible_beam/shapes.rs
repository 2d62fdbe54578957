//! The shape functions of the assumed-mode beam models (`modal.rs`): the free-vibration modes
//! of the uniform Euler-Bernoulli beam and rod, and the static Hermite and linear
//! interpolants, each with its first three derivatives; the roots of the bending frequency
//! equations; and the Gauss-Legendre rules that integrate the models' matrices.
//!
//! Bending modes (`beta = z/L`, `z` the `i`-th root of `1 + cos z cosh z = 0` clamped-free,
//! of `1 - cos z cosh z = 0` clamped-clamped):
//!
//! ```text
//! phi(x) = cosh bx - cos bx - sigma (sinh bx - sin bx),
//! sigma  = (cosh bL + cos bL)/(sinh bL + sin bL)   (clamped-free),
//!          (cosh bL - cos bL)/(sinh bL - sin bL)   (clamped-clamped),
//! ```
//!
//! left unnormalised (the classical form: `int_0^L phi^2 = L`, tip value `+-2` clamped-free;
//! tested). They are evaluated without cancellation: with `E+ = e^{bx}`, `E- = e^{-bx}`,
//! `A = ((1 - sigma) E+ + (1 + sigma) E-)/2`, `B = ((1 - sigma) E+ - (1 + sigma) E-)/2`,
//! `phi = A - cos bx + sigma sin bx`, `phi' = b (B + sin bx + sigma cos bx)`,
//! `phi'' = b^2 (A + cos bx - sigma sin bx)`, `phi''' = b^3 (B - sin bx - sigma cos bx)`, and
//! `1 - sigma` formed directly (`(-e^{-bL} + sin bL - cos bL)/(sinh bL + sin bL)` clamped-free,
//! `(-e^{-bL} - sin bL + cos bL)/(sinh bL - sin bL)` clamped-clamped), with every hyperbolic
//! function of `bL` scaled by `e^{-bL}` so that no mode index overflows. The roots come from
//! Newton's method on the bounded forms `cos z + sech z = 0` and `cos z - sech z = 0`, started
//! at their asymptotes `(2i - 1) pi/2` and `(2i + 1) pi/2`. Rod modes: `sin((2i - 1) pi x/(2L))`
//! (clamped-free), `sin(i pi x/L)` (clamped-clamped). Hermite cubics on `xi = x/L`: unit value,
//! slope at 0, value, slope at `L`; linear: `1 - xi`, `xi`.
//!
//! Invariants (tested): the roots satisfy their equations to 1e-12; every derivative agrees
//! with central differences of the one below; the modes satisfy their boundary conditions and
//! are orthogonal in mass; the Gauss rules are exact to degree `2n - 1`. Where it fails: the
//! absolute round-off of `phi` is that of its terms (`~1e-16`), so its relative accuracy is
//! lost where `phi` itself vanishes (`phi ~ x^2` at the clamp); a mode index of 0, a Hermite
//! index above 3 or a linear one above 1 is refused by [`Shape::validate`] and makes `eval`
//! panic.
use std::f64::consts::PI;

/// One shape function on `[0, L]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// The `i`-th (from 1) bending mode of the clamped-free beam.
    ClampedFreeBending(usize),
    /// The `i`-th (from 1) bending mode of the clamped-clamped beam.
    ClampedClampedBending(usize),
    /// The `i`-th (from 1) axial mode of the clamped-free rod.
    ClampedFreeRod(usize),
    /// The `i`-th (from 1) axial mode of the clamped-clamped rod.
    ClampedClampedRod(usize),
    /// Hermite cubic `0..4`: unit value at 0, unit slope at 0, unit value at `L`, unit slope
    /// at `L`.
    Hermite(usize),
    /// Linear `0..2`: `1 - x/L`, `x/L`.
    Linear(usize),
}

impl Shape {
    /// An error when the index is out of range (modes from 1, Hermite `0..4`, linear `0..2`).
    pub fn validate(&self) -> Result<(), String> {
        let ok = match *self {
            Shape::ClampedFreeBending(i)
            | Shape::ClampedClampedBending(i)
            | Shape::ClampedFreeRod(i)
            | Shape::ClampedClampedRod(i) => i >= 1,
            Shape::Hermite(i) => i < 4,
            Shape::Linear(i) => i < 2,
        };
        if ok {
            Ok(())
        } else {
            Err(format!("{self:?}: index out of range"))
        }
    }

    /// The value and the first three derivatives in `x` at `x` on a beam of length `l`.
    ///
    /// # Panics
    ///
    /// On an index that [`Shape::validate`] refuses.
    ///
    /// # Example
    ///
    /// ```
    /// use mbdbench::model::flexible_beam::shapes::Shape;
    ///
    /// let [v, d1, d2, d3] = Shape::ClampedFreeBending(1).eval(10.0, 10.0);
    /// assert!((v - 2.0).abs() < 1e-3 && d2.abs() < 1e-12 && d3.abs() < 1e-12);
    /// assert!(d1 > 0.0);
    /// assert_eq!(Shape::Hermite(2).eval(10.0, 10.0)[0], 1.0);
    /// ```
    pub fn eval(&self, x: f64, l: f64) -> [f64; 4] {
        match *self {
            Shape::ClampedFreeBending(i) => bending(clamped_free_root(i), x, l, false),
            Shape::ClampedClampedBending(i) => bending(clamped_clamped_root(i), x, l, true),
            Shape::ClampedFreeRod(i) => {
                assert!(i >= 1, "mode index from 1");
                rod((2 * i - 1) as f64 * PI / (2.0 * l), x)
            }
            Shape::ClampedClampedRod(i) => {
                assert!(i >= 1, "mode index from 1");
                rod(i as f64 * PI / l, x)
            }
            Shape::Hermite(i) => hermite(i, x, l),
            Shape::Linear(0) => [1.0 - x / l, -1.0 / l, 0.0, 0.0],
            Shape::Linear(1) => [x / l, 1.0 / l, 0.0, 0.0],
            Shape::Linear(i) => panic!("linear shape {i} out of range 0..2"),
        }
    }
}

/// `sin(k x)` and its derivatives.
fn rod(k: f64, x: f64) -> [f64; 4] {
    let (s, c) = (k * x).sin_cos();
    [s, k * c, -k * k * s, -k * k * k * c]
}

/// The Hermite cubic `i` on `[0, l]` and its derivatives.
fn hermite(i: usize, x: f64, l: f64) -> [f64; 4] {
    let xi = x / l;
    let (x2, x3) = (xi * xi, xi * xi * xi);
    match i {
        0 => [
            1.0 - 3.0 * x2 + 2.0 * x3,
            6.0 * (x2 - xi) / l,
            (12.0 * xi - 6.0) / (l * l),
            12.0 / (l * l * l),
        ],
        1 => [
            l * (xi - 2.0 * x2 + x3),
            1.0 - 4.0 * xi + 3.0 * x2,
            (6.0 * xi - 4.0) / l,
            6.0 / (l * l),
        ],
        2 => [
            3.0 * x2 - 2.0 * x3,
            6.0 * (xi - x2) / l,
            (6.0 - 12.0 * xi) / (l * l),
            -12.0 / (l * l * l),
        ],
        3 => [
            l * (x3 - x2),
            3.0 * x2 - 2.0 * xi,
            (6.0 * xi - 2.0) / l,
            6.0 / (l * l),
        ],
        _ => panic!("Hermite shape {i} out of range 0..4"),
    }
}

/// The bending mode with root `z = beta L` at `x` and its derivatives, in the
/// cancellation-free form of the module's header.
fn bending(z: f64, x: f64, l: f64, clamped_clamped: bool) -> [f64; 4] {
    let b = z / l;
    let el = (-z).exp();
    let (sl, cl) = z.sin_cos();
    // sinh z +- sin z = (1 - el^2 +- 2 el sin z)/(2 el), cosh z +- cos z likewise: the
    // factors 1/(2 el) cancel in sigma; in 1 - sigma one el is left, which multiplies e^{bx}.
    let (sigma, one_minus_scaled) = if clamped_clamped {
        let den = 1.0 - el * el - 2.0 * el * sl;
        (
            (1.0 + el * el - 2.0 * el * cl) / den,
            2.0 * (-el - sl + cl) / den,
        )
    } else {
        let den = 1.0 - el * el + 2.0 * el * sl;
        (
            (1.0 + el * el + 2.0 * el * cl) / den,
            2.0 * (-el + sl - cl) / den,
        )
    };
    // (1 - sigma) e^{bx} = one_minus_scaled e^{b x - z}; (1 + sigma) = 2 - (1 - sigma).
    let plus = one_minus_scaled * (b * x - z).exp();
    let minus = (2.0 - one_minus_scaled * el) * (-b * x).exp();
    let (a, bb) = (0.5 * (plus + minus), 0.5 * (plus - minus));
    let (s, c) = (b * x).sin_cos();
    [
        a - c + sigma * s,
        b * (bb + s + sigma * c),
        b * b * (a + c - sigma * s),
        b * b * b * (bb - s - sigma * c),
    ]
}

/// Newton's method on `cos z + sign sech z = 0` from `z0`, to round-off.
fn root(z0: f64, sign: f64) -> f64 {
    let mut z = z0;
    for _ in 0..60 {
        let sech = 1.0 / z.cosh();
        let f = z.cos() + sign * sech;
        let df = -z.sin() - sign * sech * z.tanh();
        let dz = f / df;
        z -= dz;
        if dz.abs() <= 1e-16 * z {
            break;
        }
    }
    z
}

/// `beta_i L` of the clamped-free beam: the `i`-th (from 1) root of `1 + cos z cosh z = 0`
/// (1.8751, 4.6941, 7.8548, 10.9955, ...).
///
/// # Panics
///
/// If `i` is 0.
pub fn clamped_free_root(i: usize) -> f64 {
    assert!(i >= 1, "mode index from 1");
    root((2 * i - 1) as f64 * PI / 2.0, 1.0)
}

/// `beta_i L` of the clamped-clamped beam: the `i`-th (from 1) root of
/// `1 - cos z cosh z = 0` (4.7300, 7.8532, ...).
///
/// # Panics
///
/// If `i` is 0.
pub fn clamped_clamped_root(i: usize) -> f64 {
    assert!(i >= 1, "mode index from 1");
    root((2 * i + 1) as f64 * PI / 2.0, -1.0)
}

/// The `n`-point Gauss-Legendre rule on `[0, 1]` as `(node, weight)`, nodes ascending (exact
/// for polynomials of degree `2n - 1`): Newton on the Legendre recurrence.
///
/// # Panics
///
/// If `n` is 0.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n >= 1, "a Gauss rule needs a point");
    let mut rule = Vec::with_capacity(n);
    for i in 0..n.div_ceil(2) {
        let mut z = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let w = 1.0 / ((1.0 - z * z) * dp * dp);
        rule.push((0.5 * (1.0 - z), w));
        if 2 * i + 1 != n {
            rule.push((0.5 * (1.0 + z), w));
        }
    }
    rule.sort_by(|a, b| a.0.total_cmp(&b.0));
    rule
}

/// The composite rule of `n_pt`-point Gauss-Legendre on `n_sub` equal subintervals of
/// `[0, l]`, as `(x, weight)`.
pub fn composite_rule(l: f64, n_sub: usize, n_pt: usize) -> Vec<(f64, f64)> {
    let base = gauss_legendre(n_pt);
    let h = l / n_sub as f64;
    (0..n_sub)
        .flat_map(|k| base.iter().map(move |(x, w)| ((k as f64 + x) * h, w * h)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: f64 = 10.0;

    /// The roots satisfy their frequency equations (in the bounded and the classical form)
    /// to 1e-12 and match the tabulated values.
    #[test]
    fn roots_satisfy_their_equations() {
        let cf = [1.8751, 4.6941, 7.8548, 10.9955];
        let cc = [4.7300, 7.8532, 10.9956, 14.1372];
        for i in 1..=30 {
            let (z, y) = (clamped_free_root(i), clamped_clamped_root(i));
            assert!((z.cos() + 1.0 / z.cosh()).abs() < 1e-12, "CF {i}");
            assert!((y.cos() - 1.0 / y.cosh()).abs() < 1e-12, "CC {i}");
            assert!(
                (1.0 + z.cos() * z.cosh()).abs() < 1e-12 * z.cosh(),
                "CF {i}"
            );
            assert!(
                (1.0 - y.cos() * y.cosh()).abs() < 1e-12 * y.cosh(),
                "CC {i}"
            );
            // Each root is the i-th: it lies within pi/2 of its asymptote.
            assert!((z - (2 * i - 1) as f64 * PI / 2.0).abs() < 0.31, "CF {i}");
            assert!((y - (2 * i + 1) as f64 * PI / 2.0).abs() < 0.02, "CC {i}");
            if i <= 4 {
                assert!((z - cf[i - 1]).abs() < 5e-5 && (y - cc[i - 1]).abs() < 5e-5);
            }
        }
        eprintln!(
            "roots: CF {:.12} {:.12}, CC {:.12} {:.12}",
            clamped_free_root(1),
            clamped_free_root(2),
            clamped_clamped_root(1),
            clamped_clamped_root(2)
        );
    }

    fn all_shapes() -> Vec<Shape> {
        let mut s = Vec::new();
        for i in [1, 2, 4, 8] {
            s.extend([
                Shape::ClampedFreeBending(i),
                Shape::ClampedClampedBending(i),
                Shape::ClampedFreeRod(i),
                Shape::ClampedClampedRod(i),
            ]);
        }
        s.extend((0..4).map(Shape::Hermite));
        s.extend((0..2).map(Shape::Linear));
        s
    }

    /// Every derivative agrees with the central difference of the one below, relative to the
    /// derivative's scale (1e-7).
    #[test]
    fn derivatives_agree_with_differences() {
        let h = 1e-5;
        let mut worst = 0.0f64;
        for shape in all_shapes() {
            // The scale of the k-th derivative: max |phi| times the wavenumber^k.
            let (mut vmax, mut kmax) = (0.0f64, 1.0 / L);
            for j in 0..=200 {
                let e = shape.eval(L * j as f64 / 200.0, L);
                vmax = vmax.max(e[0].abs());
                if e[0].abs() > 1e-3 {
                    kmax = kmax.max((e[2] / e[0]).abs().sqrt());
                }
            }
            for j in 1..20 {
                let x = L * j as f64 / 20.0 + 0.013;
                let (p, m, e) = (shape.eval(x + h, L), shape.eval(x - h, L), shape.eval(x, L));
                for k in 0..3 {
                    let fd = (p[k] - m[k]) / (2.0 * h);
                    let scale = vmax * kmax.powi(k as i32 + 1);
                    let err = (fd - e[k + 1]).abs() / scale;
                    worst = worst.max(err);
                    assert!(err < 1e-7, "{shape:?} d{} at {x}: {err:e}", k + 1);
                }
            }
        }
        eprintln!("shape derivatives vs differences: worst relative {worst:.2e}");
    }

    /// The modes satisfy their boundary conditions (relative to b^k max|phi|, 1e-9): CF
    /// bending phi(0) = phi'(0) = phi''(L) = phi'''(L) = 0, CC bending value and slope zero at
    /// both ends, rods zero at the clamps and (CF) zero strain at the tip; the Hermite and
    /// linear shapes have their unit end values.
    #[test]
    fn modes_satisfy_their_boundary_conditions() {
        let mut worst = 0.0f64;
        for i in 1..=12 {
            let b = clamped_free_root(i) / L;
            let (a, e) = (
                Shape::ClampedFreeBending(i).eval(0.0, L),
                Shape::ClampedFreeBending(i).eval(L, L),
            );
            for err in [a[0], a[1] / b, e[2] / (b * b), e[3] / (b * b * b)] {
                worst = worst.max(err.abs() / 2.0);
                assert!(err.abs() < 2e-9, "CF {i}: {a:?} {e:?}");
            }
            assert!((e[0].abs() - 2.0).abs() < 1e-9, "CF tip value {}", e[0]);
            let b = clamped_clamped_root(i) / L;
            let (a, e) = (
                Shape::ClampedClampedBending(i).eval(0.0, L),
                Shape::ClampedClampedBending(i).eval(L, L),
            );
            for err in [a[0], a[1] / b, e[0], e[1] / b] {
                worst = worst.max(err.abs() / 2.0);
                assert!(err.abs() < 2e-9, "CC {i}: {a:?} {e:?}");
            }
            let r = Shape::ClampedFreeRod(i);
            assert!(r.eval(0.0, L)[0].abs() < 1e-15 && r.eval(L, L)[1].abs() < 1e-12);
            let r = Shape::ClampedClampedRod(i);
            assert!(r.eval(0.0, L)[0].abs() < 1e-15 && r.eval(L, L)[0].abs() < 1e-12);
        }
        let ends = |s: Shape| [s.eval(0.0, L), s.eval(L, L)];
        let want = [
            [[1.0, 0.0], [0.0, 0.0]],
            [[0.0, 1.0], [0.0, 0.0]],
            [[0.0, 0.0], [1.0, 0.0]],
            [[0.0, 0.0], [0.0, 1.0]],
        ];
        for (i, w) in want.iter().enumerate() {
            let [a, e] = ends(Shape::Hermite(i));
            for (got, w) in [a[0], a[1], e[0], e[1]].iter().zip(w.concat()) {
                assert!((got - w).abs() < 1e-14, "Hermite {i}");
            }
        }
        assert_eq!(ends(Shape::Linear(0))[0][0], 1.0);
        assert_eq!(ends(Shape::Linear(1))[1][0], 1.0);
        eprintln!("mode boundary conditions: worst relative {worst:.2e}");
    }

    /// The bending modes of each family are orthogonal in mass (int phi_i phi_j, relative to
    /// the diagonal, 1e-10) and in stiffness (int phi_i'' phi_j''), with int phi_i^2 = L;
    /// the rod modes likewise.
    #[test]
    fn modes_are_orthogonal() {
        let rule = composite_rule(L, 32, 8);
        let n = 8;
        let mut worst = 0.0f64;
        type Family = fn(usize) -> Shape;
        let families: [Family; 4] = [
            Shape::ClampedFreeBending,
            Shape::ClampedClampedBending,
            Shape::ClampedFreeRod,
            Shape::ClampedClampedRod,
        ];
        for family in families {
            let (mut m, mut k) = (vec![vec![0.0; n]; n], vec![vec![0.0; n]; n]);
            for &(x, w) in &rule {
                let e: Vec<[f64; 4]> = (1..=n).map(|i| family(i).eval(x, L)).collect();
                for i in 0..n {
                    for j in 0..n {
                        m[i][j] += w * e[i][0] * e[j][0];
                        k[i][j] += w * e[i][2] * e[j][2];
                    }
                }
            }
            for i in 0..n {
                let want = if matches!(
                    family(1),
                    Shape::ClampedFreeRod(_) | Shape::ClampedClampedRod(_)
                ) {
                    L / 2.0
                } else {
                    L
                };
                assert!(
                    (m[i][i] / want - 1.0).abs() < 1e-12,
                    "{:?}: {}",
                    family(i + 1),
                    m[i][i]
                );
                for j in 0..n {
                    if i != j {
                        let (em, ek) = (
                            m[i][j].abs() / (m[i][i] * m[j][j]).sqrt(),
                            k[i][j].abs() / (k[i][i] * k[j][j]).sqrt(),
                        );
                        worst = worst.max(em).max(ek);
                        assert!(
                            em < 1e-10 && ek < 1e-10,
                            "{:?} {i} {j}: {em:e} {ek:e}",
                            family(1)
                        );
                    }
                }
            }
        }
        eprintln!("mode orthogonality (8 modes per family): worst relative {worst:.2e}");
    }

    /// The Gauss-Legendre rules integrate x^k exactly for k <= 2n - 1, miss x^{2n} by the
    /// theoretical error (n <= 6, above which it drowns in round-off), and the composite rule
    /// integrates over [0, L].
    #[test]
    fn gauss_rules_are_exact_to_their_degree() {
        for n in 1..=10 {
            let rule = gauss_legendre(n);
            assert_eq!(rule.len(), n);
            for k in 0..=2 * n {
                let got: f64 = rule.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                let err = (got - 1.0 / (k + 1) as f64).abs();
                if k < 2 * n {
                    assert!(err < 1e-14, "n {n} k {k}: {err:e}");
                } else if n <= 6 {
                    // The error of x^{2n}: (n!)^4 / ((2n + 1) ((2n)!)^2) on [0, 1].
                    let fact = |m: usize| (1..=m).map(|i| i as f64).product::<f64>();
                    let want = fact(n).powi(4) / ((2 * n + 1) as f64 * fact(2 * n).powi(2));
                    assert!(
                        (err / want - 1.0).abs() < 1e-3,
                        "n {n}: {err:e} vs {want:e}"
                    );
                }
            }
        }
        let got: f64 = composite_rule(L, 32, 8)
            .iter()
            .map(|(x, w)| w * x * x)
            .sum();
        assert!((got / (L * L * L / 3.0) - 1.0).abs() < 1e-14);
    }
}
