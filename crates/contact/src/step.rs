//! One load step of a contact problem on a fixed tangent stiffness: the
//! geometric loop (REAC_GEOM) around the multiplier algorithms of [`dual`].
//!
//! This is complete for linear elastic structures (where Newton converges
//! in one iteration, as in code_aster's ZZZZ237 and Hertz tests) and is the
//! inner contact solve of a Newton iteration otherwise.
//!
//! [`dual`]: crate::dual

use aster_fem::{DofNumbering, InequalityRow};
use aster_mesh::Mesh;

use crate::dual::{solve_dual_cached, ColumnCache, DualAlgorithm, IndexedRow, StiffnessSolve};
use crate::error::ContactError;
use crate::source::{ZoneContact, ZoneLaw};
use crate::zone::{ContactDefinition, ContinueAlgo, DiscreteAlgo, GeomLoop, Resolution};

/// What a step did.
#[derive(Clone, Debug, PartialEq)]
pub struct StepReport {
    /// Total displacement at convergence (solver numbering).
    pub u: Vec<f64>,
    /// Geometric iterations (pairings).
    pub geom_iterations: usize,
    /// Iterations of the contact algorithm, summed over pairings.
    pub contact_iterations: usize,
    /// Solves with K done by the contact algorithm.
    pub solves: usize,
    /// Number of active contact rows at convergence.
    pub active: usize,
    /// Wall seconds spent pairing and building rows (all geometric
    /// iterations), for profiles of where a step's time goes.
    pub pairing_seconds: f64,
}

/// Solves one step: `u_free` is the displacement without contact (with
/// this step's loads and imposed displacements); `u_start` the displacement
/// the pairing starts from (the previous step's). The zones keep their
/// multipliers for CONT_NOEU.
pub fn solve_step(
    def: &ContactDefinition,
    zones: &mut [ZoneContact],
    mesh: &Mesh,
    dofs: &DofNumbering,
    k: &dyn StiffnessSolve,
    u_free: &[f64],
    u_start: &[f64],
) -> Result<StepReport, ContactError> {
    let mut cache = ColumnCache::new();
    solve_step_cached(def, zones, mesh, dofs, k, u_free, u_start, &mut cache)
}

/// [`solve_step`] keeping the columns K⁻¹aⱼ in `cache` (filled with the
/// same K): a geometric iteration, or a later step, whose rows are
/// unchanged on the free DOFs does not solve for them again.
#[allow(clippy::too_many_arguments)]
pub fn solve_step_cached(
    def: &ContactDefinition,
    zones: &mut [ZoneContact],
    mesh: &Mesh,
    dofs: &DofNumbering,
    k: &dyn StiffnessSolve,
    u_free: &[f64],
    u_start: &[f64],
    cache: &mut ColumnCache,
) -> Result<StepReport, ContactError> {
    let algo = algorithm(def, zones)?;
    let (max_geom, resi_geom) = match def.geom_loop() {
        GeomLoop::Automatique {
            iter_maxi,
            resi_geom,
        } => (iter_maxi.max(1), Some(resi_geom)),
        GeomLoop::Controle { nb_iter } => (nb_iter.max(1), None),
        GeomLoop::Sans => (1, None),
    };
    let mut u = u_start.to_vec();
    let mut report = StepReport {
        u: Vec::new(),
        geom_iterations: 0,
        contact_iterations: 0,
        solves: 0,
        active: 0,
        pairing_seconds: 0.0,
    };
    let mut warm: Option<Vec<bool>> = None;
    for it in 0..max_geom {
        let pairing_start = std::time::Instant::now();
        let x = positions(mesh, dofs, &u);
        let mut rows = Vec::new();
        let mut eps = Vec::new();
        let mut counts = Vec::new();
        for z in zones.iter_mut() {
            let r = z.pair(mesh, &x)?;
            counts.push(r.len());
            eps.extend(z.row_penalties());
            for row in r {
                rows.push(index_row(&row, dofs, mesh)?);
            }
        }
        report.pairing_seconds += pairing_start.elapsed().as_secs_f64();
        let warm_ok = warm
            .as_ref()
            .filter(|w| w.len() == rows.len())
            .map(|w| w.as_slice());
        let sol = solve_dual_cached(k, u_free, &rows, &eps, algo(rows.len()), warm_ok, cache)?;
        report.geom_iterations = it + 1;
        report.contact_iterations += sol.iterations;
        report.solves += sol.solves;
        report.active = sol.active.iter().filter(|a| **a).count();
        let mut start = 0;
        for (z, n) in zones.iter_mut().zip(&counts) {
            z.set_multipliers(&sol.lambda[start..start + n]);
            start += n;
        }
        let change = sol
            .u
            .iter()
            .zip(&u)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        let size = sol.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        warm = Some(sol.active);
        u = sol.u;
        if let Some(r) = resi_geom {
            if change <= r * size.max(f64::MIN_POSITIVE) {
                break;
            }
            if it + 1 == max_geom && max_geom > 1 {
                return Err(ContactError::NotConverged {
                    what: "geometric loop (REAC_GEOM='AUTOMATIQUE')",
                    iterations: max_geom,
                    residual: change / size.max(f64::MIN_POSITIVE),
                });
            }
        }
    }
    report.u = u;
    Ok(report)
}

/// The multiplier algorithm of a definition (as a function of the number of rows).
fn algorithm(
    def: &ContactDefinition,
    zones: &[ZoneContact],
) -> Result<impl Fn(usize) -> DualAlgorithm, ContactError> {
    enum Kind {
        Exact { mult: usize, stop: bool },
        Gcp { tol: Option<f64>, maxi: usize },
        Alm { coef: f64, maxi: usize, resi: f64 },
        Newton { coef: f64, maxi: usize },
    }
    let kind = match def {
        ContactDefinition::Discrete(d) => {
            let gcp: Vec<_> = zones
                .iter()
                .filter_map(|z| match z.law {
                    ZoneLaw::Discrete(DiscreteAlgo::Gcp {
                        resi_abso,
                        iter_maxi,
                    }) => Some((resi_abso, iter_maxi)),
                    _ => None,
                })
                .collect();
            if !gcp.is_empty() && gcp.len() != zones.len() {
                return Err(ContactError::Unsupported {
                    feature: "mixing ALGO_CONT='GCP' with other algorithms across zones".into(),
                    hint: "give every zone ALGO_CONT='GCP'".into(),
                });
            }
            match gcp.first() {
                Some(&(tol, maxi)) => Kind::Gcp { tol, maxi },
                None => Kind::Exact {
                    mult: d.iter_cont_mult.max(1),
                    stop: d.stop_singulier,
                },
            }
        }
        ContactDefinition::Continue(c) => {
            let coef = zones
                .iter()
                .find_map(|z| match z.law {
                    ZoneLaw::Continue(l) => match l.algo {
                        ContinueAlgo::Standard { coef_cont } => Some(coef_cont),
                        ContinueAlgo::Penalisation { .. } | ContinueAlgo::Lac => None,
                    },
                    _ => None,
                })
                .unwrap_or(100.0);
            let all_penalised = zones.iter().all(|z| {
                matches!(
                    z.law,
                    ZoneLaw::Continue(l) if matches!(l.algo, ContinueAlgo::Penalisation { .. })
                )
            });
            if all_penalised {
                // Pure penalty has no multiplier loop: its regularised LCP
                // is solved exactly by the active set.
                Kind::Exact {
                    mult: 4,
                    stop: true,
                }
            } else {
                match c.algo_reso_cont {
                    Resolution::Newton => Kind::Newton {
                        coef,
                        maxi: c.iter_cont_maxi,
                    },
                    Resolution::PointFixe => Kind::Alm {
                        coef,
                        maxi: c.iter_cont_maxi,
                        resi: c.resi_cont.unwrap_or(1e-10),
                    },
                }
            }
        }
    };
    Ok(move |m: usize| match kind {
        Kind::Exact { mult, stop } => DualAlgorithm::ActiveSet {
            max_iter: mult * m.max(1),
            stop_singulier: stop,
        },
        Kind::Gcp { tol, maxi } => DualAlgorithm::Gcp {
            tol,
            max_iter: maxi,
        },
        Kind::Alm { coef, maxi, resi } => DualAlgorithm::AugmentedLagrangian {
            coef,
            max_iter: maxi,
            resi,
        },
        Kind::Newton { coef, maxi } => DualAlgorithm::SemiSmoothNewton {
            coef,
            max_iter: maxi.max(2 * m + 2),
        },
    })
}

/// Current positions X + u of all mesh nodes.
pub fn positions(mesh: &Mesh, dofs: &DofNumbering, u: &[f64]) -> Vec<[f64; 3]> {
    let mut x = mesh.coords.clone();
    for (i, d) in dofs.dofs().iter().enumerate() {
        let c = match d.comp {
            aster_fem::Comp::DX => 0,
            aster_fem::Comp::DY => 1,
            aster_fem::Comp::DZ => 2,
            _ => continue,
        };
        if let (Some(p), Some(v)) = (x.get_mut(d.node.0 as usize), u.get(i)) {
            p[c] += v;
        }
    }
    x
}

/// A fem row in solver numbering.
pub fn index_row(
    row: &InequalityRow,
    dofs: &DofNumbering,
    mesh: &Mesh,
) -> Result<IndexedRow, ContactError> {
    let terms = row
        .terms
        .iter()
        .map(|&(d, c)| {
            dofs.index(d)
                .map(|i| (i, c))
                .ok_or_else(|| ContactError::MissingDof {
                    node: mesh
                        .node_names
                        .get(d.node.0 as usize)
                        .cloned()
                        .unwrap_or_else(|| format!("#{}", d.node.0 + 1)),
                    component: d.comp.name(),
                })
        })
        .collect::<Result<_, _>>()?;
    Ok(IndexedRow {
        terms,
        rhs: row.rhs,
    })
}
