//! The elastica against OpenSees' corotational elements on the same meshes: the tips stored
//! in `references/fiber_column/opensees/elastica.json` (`forceBeamColumn`, elastic section,
//! 5 Lobatto points; 10 and 40 elements; 20 load steps to an energy increment of 1e-24) and
//! the exact tips stored beside them (shooting; they agree with the suite's elliptic-integral
//! tips to 5.1e-15 L), read through the manifest check of the external references.
use crate::problem::{Stepping, Want};

/// With 10 (`force_based`) and 40 (`force_based_fine`) elements, the suite's tip error on
/// every load P L^2 / EI = 1, 2, 5, 10 is at most OpenSees' `forceBeamColumn` error on the
/// same mesh (to the two solvers' convergence tolerances, 1e-8 of the error; measured: the
/// two agree to 2e-10), and both are within the requirement (1.5e-3 L and 1e-4 L).
#[test]
fn elastica_at_least_as_accurate_as_opensees() {
    let refs = crate::cli::default_references();
    // Listed in the manifest with its hash, and carrying its own provenance.
    let (bytes, _, _) = super::opensees::read_listed(&refs, "elastica.json", "the elastica")
        .unwrap_or_else(|e| panic!("{e}"));
    let file: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
    for k in ["tool", "command", "accuracy_claim", "cross_check"] {
        assert!(file["provenance"][k].is_string(), "provenance.{k}");
    }
    let cases = crate::catalogue::embedded().unwrap();
    let case = cases
        .iter()
        .find(|c| c.name == "fiber_column_static")
        .unwrap();
    let family = crate::catalogue::family_of(case);
    for (alpha, scene) in [
        ("1.0", "elastica_p1"),
        ("2.0", "elastica_p2"),
        ("5.0", "elastica_p5"),
        ("10.0", "elastica_p10"),
    ] {
        let mut p = (family.compile)(case, case.scene(scene).unwrap()).unwrap();
        p.attach_reference(&refs).unwrap();
        let exact = &file["exact"][alpha];
        for (elements, formulation, bound) in
            [("10", "force_based", 1.5e-3), ("40", "force_based_fine", 1e-4)]
        {
            let tip = &file["data"]["forceBeamColumn"][elements][alpha];
            let d = |k: &str| tip[k].as_f64().unwrap() - exact[k].as_f64().unwrap();
            let theirs = d("along").hypot(d("across"));
            let v = family.find("so3", "newton_load", formulation).unwrap();
            let out = p.run(v, Stepping::Dt(0.1), Want::Scored).unwrap();
            let ours = out.scores.get("tip_error").unwrap();
            assert!(
                ours <= theirs * (1.0 + 1e-8) && ours < bound,
                "{scene}, {elements} elements: ours {ours:e}, OpenSees {theirs:e}"
            );
            assert!((ours / theirs - 1.0).abs() < 1e-8, "{ours:e} {theirs:e}");
        }
    }
}
