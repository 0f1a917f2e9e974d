//! Hertz cylinder on a rigid plane, plane strain, on the generated mesh:
//! contact half-width and peak pressure against a = √(4PR/(πE*)) and
//! p₀ = 2P/(πa), P being the load per unit length actually transmitted
//! (twice the half-model's contact force).

use aster_contact::hertz::{hertz_mesh, plane_strain_modulus, HertzMesh, HertzSolution};
use aster_contact::*;
use aster_fem::Elastic;

const E: f64 = 2e5;
const NU: f64 = 0.3;
const R: f64 = 50.0;

struct Hertz {
    /// x of each slave node and its contact force, sorted by x.
    forces: Vec<(f64, f64)>,
    load: f64,
    h: f64,
}

fn solve(n_contact: usize, algo: DiscreteAlgo, depth: f64) -> Hertz {
    let def = ContactDefinition::discrete(
        vec![Zone {
            geometry: ZoneGeometry::new("MAIT", "ESCL"),
            law: algo,
        }],
        Frottement::Sans,
    )
    .unwrap();
    solve_with(n_contact, &def, depth)
}

fn solve_with(n_contact: usize, def: &ContactDefinition, depth: f64) -> Hertz {
    let mesh = hertz_mesh(&HertzMesh::new(R, 0.15, n_contact)).unwrap();
    let (model, loads) = scenes::hertz_problem(mesh, Elastic::new(E, NU).unwrap(), depth).unwrap();
    let mut zones = ZoneContact::build_all(def, model.mesh()).unwrap();
    run_linear(def, &mut zones, &model, &loads, &[0.0, 1.0]).unwrap();
    let mesh = model.mesh();
    let mut forces: Vec<(f64, f64)> = zones[0]
        .nodal_forces()
        .into_iter()
        .map(|(n, f)| (mesh.coord(n)[0], f))
        .collect();
    forces.sort_by(|a, b| a.0.total_cmp(&b.0));
    let load = 2.0 * forces.iter().map(|f| f.1).sum::<f64>();
    Hertz {
        forces,
        load,
        h: R * 0.15 / n_contact as f64,
    }
}

fn analytic(load: f64) -> HertzSolution {
    HertzSolution::new(load, R, plane_strain_modulus(E, NU, f64::INFINITY, 0.0))
}

#[test]
fn hertz_half_width_and_peak_pressure() {
    let s = solve(30, DiscreteAlgo::Contrainte, 0.25);
    let exact = analytic(s.load);
    // The refined sector (0.15 rad) must hold the contact.
    assert!(
        exact.half_width < 0.5 * 0.15 * R,
        "a = {}",
        exact.half_width
    );
    // Peak pressure from the symmetry node: its tributary length is h/2.
    let p0 = s.forces[0].1 / (s.h / 2.0);
    let err_p0 = (p0 - exact.peak_pressure).abs() / exact.peak_pressure;
    // Contact half-width: between the last loaded node and the next one.
    let last = s.forces.iter().rposition(|f| f.1 > 0.0).unwrap();
    let (x_in, x_out) = (s.forces[last].0, s.forces[last + 1].0);
    eprintln!(
        "Hertz n=30: P = {:.1}, a = {:.4} (nodes {x_in:.4}..{x_out:.4}), p0 = {p0:.1} vs {:.1} ({:.2}%)",
        s.load,
        exact.half_width,
        exact.peak_pressure,
        100.0 * err_p0
    );
    assert!(err_p0 < 0.03, "peak pressure error {:.2}%", 100.0 * err_p0);
    assert!(
        x_in <= exact.half_width + s.h && x_out >= exact.half_width - s.h,
        "a = {} not in [{x_in}, {x_out}] ± h",
        exact.half_width
    );
    // Pressure profile inside the contact (away from its edge) within 5% of p₀.
    for w in s
        .forces
        .windows(3)
        .filter(|w| w[1].0 < 0.7 * exact.half_width && w[1].0 > 0.0)
    {
        let p = w[1].1 / ((w[2].0 - w[0].0) / 2.0);
        assert!(
            (p - exact.pressure(w[1].0)).abs() < 0.05 * exact.peak_pressure,
            "p({}) = {p}",
            w[1].0
        );
    }
}

#[test]
fn hertz_gcp_and_penalty_agree_with_the_exact_method() {
    let exact = solve(12, DiscreteAlgo::Contrainte, 0.25);
    let gcp = solve(
        12,
        DiscreteAlgo::Gcp {
            resi_abso: None,
            iter_maxi: 0,
        },
        0.25,
    );
    let pen = solve(12, DiscreteAlgo::Penalisation { e_n: 1e9 }, 0.25);
    let fmax = exact.forces.iter().map(|f| f.1).fold(0.0, f64::max);
    for ((a, b), c) in exact.forces.iter().zip(&gcp.forces).zip(&pen.forces) {
        assert!((a.1 - b.1).abs() < 1e-6 * fmax, "GCP {} vs {}", b.1, a.1);
        assert!(
            (a.1 - c.1).abs() < 2e-2 * fmax,
            "penalty {} vs {}",
            c.1,
            a.1
        );
    }
}

#[test]
fn hertz_continuous_formulation_with_every_integration_rule() {
    let exact = solve(12, DiscreteAlgo::Contrainte, 0.25);
    for integration in [
        Integration::Auto,
        Integration::Gauss(3),
        Integration::Simpson(1),
        Integration::NCotes(3),
    ] {
        for algo in [
            ContinueAlgo::Standard { coef_cont: 100.0 },
            ContinueAlgo::Penalisation {
                coef_pena_cont: 1e8,
            },
        ] {
            let def = ContactDefinition::continuous(
                vec![Zone {
                    geometry: ZoneGeometry::new("MAIT", "ESCL"),
                    law: ContinueLaw { algo, integration },
                }],
                Frottement::Sans,
            )
            .unwrap();
            let s = solve_with(12, &def, 0.25);
            // Same transmitted load within 1 %, same peak pressure within 5 %.
            assert!(
                (s.load - exact.load).abs() < 0.01 * exact.load,
                "{integration:?} {algo:?}: P = {} vs {}",
                s.load,
                exact.load
            );
            let p0 = s.forces[0].1 / (s.h / 2.0);
            let p0_exact = exact.forces[0].1 / (exact.h / 2.0);
            assert!(
                (p0 - p0_exact).abs() < 0.05 * p0_exact,
                "{integration:?} {algo:?}: p0 = {p0} vs {p0_exact}"
            );
        }
    }
}
