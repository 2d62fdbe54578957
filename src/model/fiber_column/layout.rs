//! Fiber layouts: rectangular patches divided into a grid of fibers and straight layers of
//! bars, turned into the fibers of a [`FiberSection`] (OpenSees' `patch rect` and `layer
//! straight`, with the same fiber positions: patch fibers at the centres of equal cells, bars
//! equally spaced from one end of the layer to the other). The case loader checks a layout
//! without making its fibers ([`check_layout`]) and keeps it as a [`SectionSpec`]; a run
//! makes the fibers.
//!
//! Coordinates are the section's local `y` (the depth, in the plane of bending) and `z` (the
//! width). A layout is checked against the section's outline `|y| <= depth/2`,
//! `|z| <= width/2`: a patch or bar outside it is refused with its name, as is a patch with
//! no fibers or a non-positive area. Bars do not displace the concrete under them (as in
//! OpenSees' layouts of the same column), which overstates the concrete area by the bars'
//! area (0.5 % here).
use super::material::Material;
use super::section::{ElasticSection, Fiber, FiberSection, Section};

/// A rectangle `[y0, y1] x [z0, z1]` divided into `ny x nz` fibers of one material.
#[derive(Debug, Clone)]
pub struct Patch {
    pub name: String,
    pub material: Material,
    pub y: [f64; 2],
    pub z: [f64; 2],
    pub ny: usize,
    pub nz: usize,
}

/// `n` bars of area `area` equally spaced from `(y[0], z[0])` to `(y[1], z[1])` (one bar at
/// the first point when `n = 1`).
#[derive(Debug, Clone)]
pub struct Layer {
    pub name: String,
    pub material: Material,
    pub y: [f64; 2],
    pub z: [f64; 2],
    pub n: usize,
    pub area: f64,
}

/// Builds the fiber section of `patches` and `layers` inside a `depth x width` outline.
///
/// # Example
///
/// ```
/// use mbdbench::model::fiber_column::layout::{Patch, fiber_section};
/// use mbdbench::model::fiber_column::material::{Elastic, ElasticParams, Material};
///
/// let m = Material::Elastic(Elastic::new(ElasticParams { e: 1.0 }).unwrap());
/// let p = Patch { name: "core".into(), material: m, y: [-0.5, 0.5], z: [-0.5, 0.5], ny: 4, nz: 2 };
/// let s = fiber_section(1.0, 1.0, &[p], &[]).unwrap();
/// assert_eq!(s.fibers().len(), 8);
/// let area: f64 = s.fibers().iter().map(|f| f.area).sum();
/// assert!((area - 1.0).abs() < 1e-15);
/// ```
pub fn fiber_section(
    depth: f64,
    width: f64,
    patches: &[Patch],
    layers: &[Layer],
) -> Result<FiberSection, String> {
    check_layout(depth, width, patches, layers)?;
    let mut fibers = Vec::new();
    for p in patches {
        let (dy, dz) = (p.y[1] - p.y[0], p.z[1] - p.z[0]);
        let area = dy * dz / (p.ny * p.nz) as f64;
        for i in 0..p.ny {
            for j in 0..p.nz {
                fibers.push(Fiber {
                    y: p.y[0] + dy * (i as f64 + 0.5) / p.ny as f64,
                    z: p.z[0] + dz * (j as f64 + 0.5) / p.nz as f64,
                    area,
                    material: p.material,
                });
            }
        }
    }
    for l in layers {
        for k in 0..l.n {
            let (y, z) = bar(l, k);
            fibers.push(Fiber {
                y,
                z,
                area: l.area,
                material: l.material,
            });
        }
    }
    FiberSection::new(fibers)
}

/// Bar `k` of a layer: equally spaced from `(y[0], z[0])` to `(y[1], z[1])`.
fn bar(l: &Layer, k: usize) -> (f64, f64) {
    let s = if l.n == 1 {
        0.0
    } else {
        k as f64 / (l.n - 1) as f64
    };
    (
        l.y[0] + s * (l.y[1] - l.y[0]),
        l.z[0] + s * (l.z[1] - l.z[0]),
    )
}

/// Checks a layout without making its fibers (the case loader's check, whatever the counts):
/// the errors [`fiber_section`] gives, in the same order. A layer's bars lie on a segment
/// and each coordinate of `bar` is monotone in `k` (rounding included), so the bars inside
/// the outline are a run from the first: a bisection finds the first bar outside.
pub fn check_layout(
    depth: f64,
    width: f64,
    patches: &[Patch],
    layers: &[Layer],
) -> Result<(), String> {
    if !(depth > 0.0 && width > 0.0 && depth.is_finite() && width.is_finite()) {
        return Err(format!(
            "section outline {depth} x {width} must be positive"
        ));
    }
    let tol = 1e-12 * depth.max(width);
    let inside = |y: f64, z: f64| y.abs() <= 0.5 * depth + tol && z.abs() <= 0.5 * width + tol;
    for p in patches {
        if p.ny == 0 || p.nz == 0 {
            return Err(format!(
                "patch {}: {} x {} fibers (at least 1 x 1)",
                p.name, p.ny, p.nz
            ));
        }
        let (dy, dz) = (p.y[1] - p.y[0], p.z[1] - p.z[0]);
        if !(dy > 0.0 && dz > 0.0) {
            return Err(format!(
                "patch {}: y {:?}, z {:?} must be increasing ranges",
                p.name, p.y, p.z
            ));
        }
        if !inside(p.y[0], p.z[0]) || !inside(p.y[1], p.z[1]) {
            return Err(format!(
                "patch {}: y {:?}, z {:?} lies outside the {depth} x {width} section",
                p.name, p.y, p.z
            ));
        }
    }
    for l in layers {
        if l.n == 0 || !(l.area > 0.0 && l.area.is_finite()) {
            return Err(format!(
                "layer {}: {} bars of area {} (need at least one bar of positive area)",
                l.name, l.n, l.area
            ));
        }
        let is_in = |k: usize| {
            let (y, z) = bar(l, k);
            inside(y, z)
        };
        let first_out = if !is_in(0) {
            Some(0)
        } else if is_in(l.n - 1) {
            None
        } else {
            // is_in(lo) and !is_in(hi).
            let (mut lo, mut hi) = (0, l.n - 1);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if is_in(mid) { lo = mid } else { hi = mid }
            }
            Some(hi)
        };
        if let Some(k) = first_out {
            let (y, z) = bar(l, k);
            return Err(format!(
                "layer {}: bar {k} at ({y}, {z}) lies outside the {depth} x {width} section",
                l.name
            ));
        }
    }
    if patches.is_empty() && layers.is_empty() {
        return Err("a fiber section needs at least one fiber".into());
    }
    Ok(())
}

/// A scene's section as the case loader keeps it: an elastic section, or a checked fiber
/// layout with its materials. The fibers are made when a run builds its column
/// ([`SectionSpec::build`]), after the case's memory and work estimate has passed, so a
/// loaded case holds nothing that grows with its fiber counts.
#[derive(Debug, Clone)]
pub enum SectionSpec {
    Elastic(ElasticSection),
    Fiber {
        depth: f64,
        width: f64,
        patches: Vec<Patch>,
        layers: Vec<Layer>,
    },
}

impl SectionSpec {
    /// The section with its fibers.
    pub fn build(&self) -> Result<Section, String> {
        Ok(match self {
            SectionSpec::Elastic(e) => Section::Elastic(*e),
            SectionSpec::Fiber {
                depth,
                width,
                patches,
                layers,
            } => Section::Fiber(fiber_section(*depth, *width, patches, layers)?),
        })
    }

    /// The fiber count (as a float: counts up to 9e15 multiply; an elastic section counts 1)
    /// and the case key of the patch or layer with the most fibers (`""` for an elastic
    /// section).
    pub fn fibers(&self) -> (f64, String) {
        let SectionSpec::Fiber {
            patches, layers, ..
        } = self
        else {
            return (1.0, String::new());
        };
        let mut total = 0.0;
        let (mut most, mut key) = (0.0, String::new());
        for (j, p) in patches.iter().enumerate() {
            let n = p.ny as f64 * p.nz as f64;
            total += n;
            if n > most {
                most = n;
                let axis = if p.ny >= p.nz { "ny" } else { "nz" };
                key = format!("section.patches[{j}].{axis}");
            }
        }
        for (j, l) in layers.iter().enumerate() {
            let n = l.n as f64;
            total += n;
            if n > most {
                most = n;
                key = format!("section.layers[{j}].n");
            }
        }
        (total, key)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fiber_column::material::{Elastic, ElasticParams};

    fn elastic() -> Material {
        Material::Elastic(Elastic::new(ElasticParams { e: 1.0 }).unwrap())
    }

    // A patch's fibers integrate area, first and second moments of its rectangle exactly
    // (area and first moments) and to the midpoint rule's O(1/n^2) (second moments).
    #[test]
    fn patch_moments() {
        let p = Patch {
            name: "p".into(),
            material: elastic(),
            y: [-0.2, 0.3],
            z: [-0.1, 0.1],
            ny: 50,
            nz: 3,
        };
        let s = fiber_section(1.0, 1.0, &[p], &[]).unwrap();
        let a: f64 = s.fibers().iter().map(|f| f.area).sum();
        let sy: f64 = s.fibers().iter().map(|f| f.area * f.y).sum();
        let iz: f64 = s.fibers().iter().map(|f| f.area * f.y * f.y).sum();
        assert!((a - 0.1).abs() < 1e-15);
        assert!((sy - 0.2 * (0.09 - 0.04) / 2.0).abs() < 1e-15);
        let exact = 0.2 * (0.027 + 0.008) / 3.0;
        let midpoint = exact - 0.1 * (0.5f64 / 50.0).powi(2) / 12.0;
        assert!((iz - midpoint).abs() < 1e-15, "{iz} {midpoint}");
    }

    // A patch or bar outside the outline, an empty patch, an empty layer and a bar of zero
    // area are refused with their names.
    #[test]
    fn bad_layouts_are_refused() {
        let p = |y: [f64; 2], ny| Patch {
            name: "cover".into(),
            material: elastic(),
            y,
            z: [-0.5, 0.5],
            ny,
            nz: 1,
        };
        let e = fiber_section(1.0, 1.0, &[p([-0.5, 0.6], 2)], &[]).unwrap_err();
        assert!(e.contains("patch cover") && e.contains("outside"), "{e}");
        let e = fiber_section(1.0, 1.0, &[p([-0.5, 0.5], 0)], &[]).unwrap_err();
        assert!(e.contains("patch cover"), "{e}");
        let l = |y: f64, n, area| Layer {
            name: "bars".into(),
            material: elastic(),
            y: [y, y],
            z: [-0.4, 0.4],
            n,
            area,
        };
        let e = fiber_section(1.0, 1.0, &[], &[l(0.7, 4, 1e-4)]).unwrap_err();
        assert!(e.contains("layer bars") && e.contains("outside"), "{e}");
        let e = fiber_section(1.0, 1.0, &[], &[l(0.2, 0, 1e-4)]).unwrap_err();
        assert!(e.contains("layer bars"), "{e}");
        let e = fiber_section(1.0, 1.0, &[], &[l(0.2, 4, 0.0)]).unwrap_err();
        assert!(e.contains("layer bars"), "{e}");
        let e = fiber_section(1.0, 1.0, &[], &[]).unwrap_err();
        assert!(e.contains("at least one fiber"), "{e}");
    }
}
