//! Times the phases of assembling and solving a plane-strain QUAD4 grid
//! (issue 5's bar: n = 707 gives 1M DOFs):
//! `cargo run --release -p aster-fem --example phases -- 707`.
//!
//! Each line gives the phase's wall time and the process CPU (user + system)
//! it used: on a shared machine the wall time mostly measures the others'
//! load, while CPU above wall means the phase ran on several cores.
//! `ASTER_FEM_TIMING=1` adds the solver's own sub-phases.

use aster_fem::assembly::{assemble_stiffness_into, restrict_owned, stiffness_pattern};
use aster_fem::linalg;
use aster_fem::scenes::{free_coords, quad4_grid};
use std::time::Instant;

/// User + system CPU seconds of this process (Linux /proc; 0 elsewhere).
fn cpu() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which is in parentheses).
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.);
    // utime and stime are fields 14 and 15 of the stat line (11, 12 here).
    (ticks(11) + ticks(12)) / 100.0
}

/// Wall and CPU time of one phase.
struct Phase {
    wall: Instant,
    cpu: f64,
}

impl Phase {
    fn start() -> Phase {
        Phase {
            wall: Instant::now(),
            cpu: cpu(),
        }
    }

    fn end(self) -> (f64, f64) {
        (self.wall.elapsed().as_secs_f64(), cpu() - self.cpu)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(224);
    let p = Phase::start();
    let (model, map) = quad4_grid(n)?;
    let coords = free_coords(&model, &map);
    let (w, c) = p.end();
    println!(
        "model: {} dofs in {w:.3} s (cpu {c:.2} s)",
        model.dofs().len()
    );

    let total = Phase::start();
    let p = Phase::start();
    let mut k = stiffness_pattern(&model);
    let (w, c) = p.end();
    println!(
        "pattern: {} non-zeros in {w:.3} s (cpu {c:.2} s)",
        k.values.len()
    );
    let p = Phase::start();
    assemble_stiffness_into(&model, &mut k)?;
    let (w, c) = p.end();
    println!("assembly: {w:.3} s (cpu {c:.2} s)");
    let p = Phase::start();
    let nfree = map.iter().filter(|&&m| m != usize::MAX).count();
    let kff = restrict_owned(k, &map, nfree);
    let (w, c) = p.end();
    println!("restrict: {} free dofs in {w:.3} s (cpu {c:.2} s)", kff.n);
    let mut b = vec![0.0; nfree];
    b[nfree - 1] = 1e6;
    let p = Phase::start();
    let r = linalg::solve_with(&kff, &b, nfree, true, Some(&coords))
        .map_err(|f| format!("solve failed: {f:?}"))?;
    let (w, c) = p.end();
    println!(
        "factorise+solve ({}): {w:.3} s (cpu {c:.2} s), backward error {:.2e}",
        if r.cholesky { "Cholesky" } else { "LU" },
        r.backward_error
    );
    let (w, c) = total.end();
    println!("pattern+assembly+restrict+factorise+solve: {w:.3} s (cpu {c:.2} s)");
    Ok(())
}
