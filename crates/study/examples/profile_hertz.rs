//! Runs one Hertz point many times (for `perf record`):
//! `cargo run --release -p aster-study --example profile_hertz -- FAMILY COEF REFINE REPS`
use aster_study::scenes::hertz::Hertz;
use aster_study::{Method, MethodFamily, Point, Scene};
use std::collections::BTreeMap;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let family = match args.get(1).map(String::as_str).unwrap_or("contrainte") {
        "penalisation" => MethodFamily::DiscretePenalisation,
        "gcp" => MethodFamily::DiscreteGcp,
        "standard" => MethodFamily::ContinuousStandard,
        "cpenal" => MethodFamily::ContinuousPenalisation,
        "unil" => MethodFamily::LiaisonUnil,
        _ => MethodFamily::DiscreteContrainte,
    };
    let coef: Option<f64> = args.get(2).and_then(|s| s.parse().ok());
    let refine: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(16);
    let reps: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(50);
    let scene = match Hertz::from_params(&BTreeMap::new()) {
        Ok(s) => s,
        Err(e) => return eprintln!("{e}"),
    };
    let method = match Method::new(family, coef) {
        Ok(m) => m,
        Err(e) => return eprintln!("{e}"),
    };
    let point = Point {
        index: 0,
        method,
        refine,
        stiffness_ratio: 1.0,
        steps: 1,
        coulomb: 0.0,
    };
    aster_study::clock::run_sequentially();
    let start = aster_study::clock::cpu_now();
    let mut sum = [0.0; 8];
    for _ in 0..reps {
        match scene.run(&point) {
            Ok(m) => {
                if let Some(p) = m.phases {
                    for (s, (_, v)) in sum.iter_mut().zip(p.named()) {
                        *s += v;
                    }
                }
            }
            Err(f) => return eprintln!("{}", f.message),
        }
    }
    let total = aster_study::clock::cpu_since(start) / reps as f64;
    let names = aster_study::Phases::default().named();
    let solver = (sum[3] + sum[4]) / reps as f64;
    print!(
        "{} n={refine}: {:.3} ms CPU per run, outside {:.0}% |",
        method.label(),
        total * 1e3,
        100.0 * (total - solver) / total
    );
    for ((name, _), s) in names.iter().zip(sum) {
        print!(" {name} {:.3}", s / reps as f64 * 1e3);
    }
    println!();
}
