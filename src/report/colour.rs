//! Colour difference for the report's palettes: sRGB (8-bit, D65) to CIELAB and the CIEDE2000
//! colour difference of two Lab colours, written from the formula as stated by Sharma, Wu and
//! Dalal, "The CIEDE2000 colour-difference formula: implementation notes, supplementary test
//! data, and mathematical observations", Color Res. Appl. 30 (2005) 21-30 (their equations
//! 1-22, kL = kC = kH = 1).
//!
//! Invariants: `delta_e2000` is symmetric and zero for equal colours; hue angles are taken in
//! degrees in [0, 360) and the mean hue follows the paper's rule for pairs whose hues differ
//! by more than 180 degrees (and for a pair with one achromatic colour). The sRGB conversion
//! uses the IEC 61966-2-1 transfer curve and the D65 white point (Xn, Yn, Zn) = (0.95047, 1,
//! 1.08883). Where it fails: nothing is clamped, so a Lab colour outside the sRGB gamut is
//! still measured; the difference is a perceptual estimate for normal colour vision only (a
//! palette that passes it may still confuse a colour-blind reader, which is why the report
//! also varies markers and dashes).
use plotters::style::RGBColor;

/// A CIELAB colour (L* in [0, 100]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lab {
    pub l: f64,
    pub a: f64,
    pub b: f64,
}

/// The linear-light value of an 8-bit sRGB channel.
fn linear(c: u8) -> f64 {
    let v = f64::from(c) / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// CIELAB of an sRGB colour (D65).
pub fn lab(c: RGBColor) -> Lab {
    let (r, g, b) = (linear(c.0), linear(c.1), linear(c.2));
    let x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    let y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    let z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    let f = |t: f64| {
        const E: f64 = 216.0 / 24389.0;
        const K: f64 = 24389.0 / 27.0;
        if t > E {
            t.cbrt()
        } else {
            (K * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(x / 0.95047), f(y), f(z / 1.08883));
    Lab {
        l: 116.0 * fy - 16.0,
        a: 500.0 * (fx - fy),
        b: 200.0 * (fy - fz),
    }
}

/// The hue angle of (a', b') in degrees, in [0, 360); 0 for an achromatic colour.
fn hue(b: f64, a: f64) -> f64 {
    if a == 0.0 && b == 0.0 {
        return 0.0;
    }
    let h = b.atan2(a).to_degrees();
    if h < 0.0 { h + 360.0 } else { h }
}

/// The CIEDE2000 difference of two Lab colours.
pub fn delta_e2000(p: Lab, q: Lab) -> f64 {
    let c1 = p.a.hypot(p.b);
    let c2 = q.a.hypot(q.b);
    let c_mean = (c1 + c2) / 2.0;
    let c7 = c_mean.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let (a1, a2) = ((1.0 + g) * p.a, (1.0 + g) * q.a);
    let (cp1, cp2) = (a1.hypot(p.b), a2.hypot(q.b));
    let (h1, h2) = (hue(p.b, a1), hue(q.b, a2));
    let dl = q.l - p.l;
    let dc = cp2 - cp1;
    let chroma_product = cp1 * cp2;
    let dh_angle = if chroma_product == 0.0 {
        0.0
    } else {
        let d = h2 - h1;
        if d > 180.0 {
            d - 360.0
        } else if d < -180.0 {
            d + 360.0
        } else {
            d
        }
    };
    let dh = 2.0 * chroma_product.sqrt() * (dh_angle.to_radians() / 2.0).sin();
    let l_mean = (p.l + q.l) / 2.0;
    let cp_mean = (cp1 + cp2) / 2.0;
    let h_mean = if chroma_product == 0.0 {
        h1 + h2
    } else if (h1 - h2).abs() <= 180.0 {
        (h1 + h2) / 2.0
    } else if h1 + h2 < 360.0 {
        (h1 + h2 + 360.0) / 2.0
    } else {
        (h1 + h2 - 360.0) / 2.0
    };
    let t = 1.0 - 0.17 * (h_mean - 30.0).to_radians().cos()
        + 0.24 * (2.0 * h_mean).to_radians().cos()
        + 0.32 * (3.0 * h_mean + 6.0).to_radians().cos()
        - 0.20 * (4.0 * h_mean - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((h_mean - 275.0) / 25.0).powi(2)).exp();
    let cp7 = cp_mean.powi(7);
    let rc = 2.0 * (cp7 / (cp7 + 25f64.powi(7))).sqrt();
    let l50 = (l_mean - 50.0).powi(2);
    let sl = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let sc = 1.0 + 0.045 * cp_mean;
    let sh = 1.0 + 0.015 * cp_mean * t;
    let rt = -(2.0 * d_theta).to_radians().sin() * rc;
    let (x, y, z) = (dl / sl, dc / sc, dh / sh);
    (x * x + y * y + z * z + rt * y * z).sqrt()
}

/// The CIEDE2000 difference of two sRGB colours.
pub fn delta_e(a: RGBColor, b: RGBColor) -> f64 {
    delta_e2000(lab(a), lab(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lab3(l: f64, a: f64, b: f64) -> Lab {
        Lab { l, a, b }
    }

    /// The formula reproduces published test pairs of Sharma, Wu and Dalal (2005), table 1
    /// (pairs 1, 7 and 17, to the table's four decimals), in both argument orders.
    #[test]
    fn sharma_test_pairs() {
        let pairs = [
            (
                lab3(50.0, 2.6772, -79.7751),
                lab3(50.0, 0.0, -82.7485),
                2.0425,
            ),
            (lab3(50.0, 0.0, 0.0), lab3(50.0, -1.0, 2.0), 2.3669),
            (lab3(50.0, 2.5, 0.0), lab3(73.0, 25.0, -18.0), 27.1492),
        ];
        for (p, q, want) in pairs {
            for got in [delta_e2000(p, q), delta_e2000(q, p)] {
                assert!((got - want).abs() < 5e-5, "{p:?} {q:?}: {got} vs {want}");
            }
        }
    }

    /// sRGB white is L* = 100 with no chroma, black L* = 0; a colour differs from itself by 0.
    #[test]
    fn srgb_end_points() {
        let w = lab(RGBColor(255, 255, 255));
        assert!(
            (w.l - 100.0).abs() < 1e-3 && w.a.abs() < 1e-2 && w.b.abs() < 1e-2,
            "{w:?}"
        );
        let k = lab(RGBColor(0, 0, 0));
        assert!(k.l.abs() < 1e-9, "{k:?}");
        assert_eq!(delta_e(RGBColor(31, 119, 180), RGBColor(31, 119, 180)), 0.0);
        assert!(delta_e(RGBColor(255, 255, 255), RGBColor(0, 0, 0)) > 99.0);
    }
}
