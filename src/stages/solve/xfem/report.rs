//! What an X-FEM solve tells: the state of each cohesive interface per instant, the run log (what was
//! simulated and eliminated, the unknowns, the Newton table, the time of each phase), readable names of
//! unknowns, and the DEPL field on the mesh nodes.

use super::assemble::Elements;
use super::setup::{names, Setup};
use crate::concepts::result::Field;
use crate::fem::elasticity::Modelisation;
use crate::stages::core::driver::StepLog;
use crate::stages::core::settings::Settings;
use crate::stages::core::solver::solver_log;
use crate::xfem::czm::CzmState;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::time::Instant;

/// The state of each cohesive interface at the end of an instant: tractions, openings, damage, energy.
pub fn zone_state(su: &Setup, el: &Elements, states: &[CzmState], x: &[f64]) -> String {
    let ndim = su.ndim();
    let mut zone_log = String::new();
    for (zi, z) in su.zones.iter().enumerate() {
        let (mut lmin, mut lmax, mut wmax, mut wmin) = (f64::MAX, f64::MIN, f64::MIN, f64::MAX);
        let mut counts = [0usize; 3];
        let mut energy = 0.0;
        for (li, l) in el.laws.iter().enumerate().filter(|(_, l)| l.zone == zi) {
            lmin = lmin.min(x[l.base]);
            lmax = lmax.max(x[l.base]);
            wmin = wmin.min(x[l.base + ndim]);
            wmax = wmax.max(x[l.base + ndim]);
            counts[states[li].state.min(2) as usize] += 1;
            energy += l.m * z.params.dissipated_energy(states[li].kappa);
        }
        let _ = writeln!(
            zone_log,
            "        {}: lambda_n in [{lmin:.9e}, {lmax:.9e}], w_n in [{wmin:.9e}, {wmax:.9e}], sound/damaged/broken {}/{}/{}, dissipated {energy:.9e}",
            su.xm.crack_names[z.crack], counts[0], counts[1], counts[2]
        );
    }
    zone_log
}

/// The run log of a solve: what was simulated, eliminated, and how.
pub fn run_log(
    cfg: &Settings,
    su: &Setup,
    el: &Elements,
    log: &StepLog,
    first: &FirstConditions,
    init: Option<&super::state::Source>,
    t_start: Instant,
) -> String {
    let (command, model) = (cfg.command.name(), &cfg.model);
    let mut s = String::new();
    let _ = writeln!(s, "  {command} on X-FEM model {} ({}):", model.label(), su.modelisation);
    let _ = writeln!(
        s,
        "    simulated : {} elasticity, Heaviside enrichment by {} interface(s) ({})",
        match su.md {
            Modelisation::DPlan => "plane-strain",
            Modelisation::CPlan => "plane-stress",
            _ => "3D",
        },
        su.xm.cracks.len(),
        su.xm.crack_names.join(", ")
    );
    for (zi, z) in su.zones.iter().enumerate() {
        let _ = writeln!(
            s,
            "                cohesive interface {} (CZM_LIN_MIX, mortar, {} packets, facet rule ORDRE_INT={}, interface measure {:.12e})",
            su.xm.crack_names[z.crack],
            z.packets.len(),
            z.order,
            el.lumped[zi].iter().sum::<f64>()
        );
        // The combinations with a component on this zone's multipliers (one of a junction counts on each).
        let nd = su.ndim();
        let mu: BTreeSet<usize> = su.xd.packets[z.crack].iter().flat_map(|&b| b + 2 * nd..b + 3 * nd).collect();
        let dead = el.dead[zi].len();
        let null: Vec<_> = el.null.iter().filter(|v| v.mu.iter().any(|(d, _)| mu.contains(d))).collect();
        let locks = null.iter().filter(|v| v.lock.is_some()).count();
        let null = null.len();
        if dead + null > 0 {
            let _ = writeln!(
                s,
                "                multipliers testing no free jump: {dead} component(s) removed, {null} combination(s) \
                 of components kept at zero{}",
                if locks > 0 {
                    format!(" ({locks} with the near-sliver jump they test held at zero)")
                } else {
                    String::new()
                }
            );
        }
    }
    for (g, name) in su.xm.crack_names.iter().enumerate() {
        if !su.zones.iter().any(|z| z.crack == g) {
            let _ = writeln!(s, "                {name}: no contact zone: free surfaces, no interface unknowns");
        }
    }
    if su.hm {
        s.push_str(&first.hm_report);
    }
    if let Some(i) = init {
        let _ = writeln!(
            s,
            "    ETAT_INIT : order {} of {} (INST={}): every unknown from its DEPL, the cohesive variables from its COHE_ELEM",
            i.order,
            i.result.label(),
            crate::text::sci(i.inst, 6, false)
        );
    }
    if let Some(n) = &cfg.newton_note {
        let _ = writeln!(s, "{n}");
    }
    for p in &first.pinned {
        let _ = writeln!(s, "    null mode : {p}");
    }
    if !log.vanished.is_empty() {
        let _ = writeln!(
            s,
            "    criterion : at steps {:?} the reactions vanished (below 1e-6 of the largest earlier one); \
             RESI_GLOB_RELA was measured against the largest earlier reaction",
            log.vanished
        );
    }
    if su.iter_cont_maxi > 0 {
        let _ = writeln!(
            s,
            "    contact loop: the cohesive variables are updated after each converged step (ITER_CONT_MAXI={} not needed)",
            su.iter_cont_maxi
        );
    }
    let flow = su.flow.as_ref().map_or(String::new(), |f| {
        format!(", {} pressures PRE1/H*PRE1, {} fracture p_f/q+/q-", f.npressure, f.n - f.first_pressure - f.npressure)
    });
    let _ = writeln!(
        s,
        "    unknowns  : {} ({} standard, {} Heaviside, {} interface λ/w/μ{flow}), {} solved after elimination of the \
         kinematic conditions",
        su.nunk(),
        su.xd.n_std,
        su.xd.n_heaviside,
        su.xd.n_interface,
        log.solved
    );
    let times = &cfg.times;
    let _ = writeln!(
        s,
        "    steps     : {} instants from {} to {}, {} computed ({} cut), {} Newton iterations in all",
        times.len() - 1,
        times[0],
        times[times.len() - 1],
        log.steps,
        log.cuts,
        log.iterations
    );
    s.push_str(&log.table);
    if let Some((info, residual, refinements)) = &log.last_solve {
        s.push_str(&solver_log(&cfg.solveur, info, *residual, *refinements));
    }
    let t = &log.solver;
    let _ = writeln!(
        s,
        "    time      : elements {:.3} s, assembly {:.3} s, factorization and solves {:.3} s, total {:.3} s",
        el.time.as_secs_f64(),
        log.assembly,
        (t.symbolic + t.factorization + t.condition + t.solve).as_secs_f64(),
        t_start.elapsed().as_secs_f64()
    );
    s
}

/// A readable name of an unknown.
pub fn label(s: &Setup, d: usize) -> String {
    let (mesh, xm, xd, zones) = (&*s.mesh, &*s.xm, &s.xd, &s.zones);
    const XYZ: [&str; 3] = ["X", "Y", "Z"];
    for (n, s) in xd.std.iter().enumerate() {
        if let Some(b) = s {
            if (*b..*b + xd.ndim).contains(&d) {
                return format!("{} D{}", mesh.node_names[n], XYZ[d - b]);
            }
        }
        for (j, &b) in xd.sets[n].iter().enumerate() {
            if (b..b + xd.ndim).contains(&d) {
                return format!("{} H{}{}", mesh.node_names[n], j + 1, XYZ[d - b]);
            }
        }
    }
    for z in zones {
        for (k, &b) in xd.packets[z.crack].iter().enumerate() {
            if (b..b + 3 * xd.ndim).contains(&d) {
                let what = ["λ", "w", "μ"][(d - b) / xd.ndim];
                return format!(
                    "{} packet {:?} {what}{}",
                    xm.crack_names[z.crack],
                    names(mesh, &z.packets[k]),
                    (d - b) % xd.ndim
                );
            }
        }
    }
    if let Some(f) = &s.flow {
        for (n, p) in f.pre1.iter().enumerate() {
            if *p == Some(d) {
                return format!("{} PRE1", mesh.node_names[n]);
            }
            if let Some(j) = f.hpre1[n].iter().position(|h| *h == Some(d)) {
                return format!("{} H{}PRE1", mesh.node_names[n], j + 1);
            }
        }
        for (zi, z) in zones.iter().enumerate() {
            for (k, &b) in f.fracture[zi].iter().enumerate() {
                if (b..b + 3).contains(&d) {
                    let what = ["PRE_FLU", "LAG_FLI", "LAG_FLS"][d - b];
                    return format!("{} packet {:?} {what}", xm.crack_names[z.crack], names(mesh, &z.packets[k]));
                }
            }
        }
    }
    format!("unknown #{d}")
}

/// SIEF_ELGA of an X-FEM solution: σ = D ε(u) at the bulk points of every model cell, in the order the
/// solver integrates them (the sub-cell points of a cut cell, sub-cell after sub-cell; the RIGI points
/// elsewhere), u recomposed from the standard and Heaviside unknowns of the point's region.
pub fn sief_field(cfg: &Settings, s: &Setup, x: &[f64]) -> crate::diag::Result<Field> {
    use crate::xfem::discrete::{bulk_points, real_gradients, BulkPoint};
    let (mesh, xm, xd, md) = (&*s.mesh, &*s.xm, &s.xd, s.md);
    let ndim = xd.ndim;
    let nsig = md.nsig();
    let mut cells = vec![None; mesh.ncells()];
    for &c in &s.model_cells {
        let name = &mesh.cell_names[c];
        let bad = |e: String| crate::diag::Error::runtime(format!("cell {name}: {e}")).at(cfg.span);
        let m = s.material(cfg, c)?;
        let (law, _) = crate::stages::core::problem::elastic_of(&m, name).map_err(|e| e.at(cfg.span))?;
        let d = law.hooke(md);
        let t = mesh.cell_types[c];
        let nodes = &mesh.cells[c];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
        let pts: Vec<BulkPoint> = if xm.cells.contains_key(&c) {
            bulk_points(t, &coords, xm, c).map_err(bad)?
        } else {
            let rule = crate::fem::elasticity::rigi_rule(t);
            rule.points.iter().map(|q| BulkPoint { xi: *q, w: 0.0, region: 0 }).collect()
        };
        let mut vals = Vec::with_capacity(pts.len() * nsig);
        for p in &pts {
            let (_, g, _) = real_gradients(t, &coords, &p.xi).ok_or_else(|| bad("degenerate cell".into()))?;
            // Displacement gradient of the recomposed field.
            let mut du = [[0.0; 3]; 3];
            for (ia, &n) in nodes.iter().enumerate() {
                let b = xd.std[n].expect("node of a model cell");
                for i in 0..ndim {
                    let mut v = x[b + i];
                    for (j, &sb) in xd.sets[n].iter().enumerate() {
                        let psi = xm.psi(n, j, p.region);
                        if psi != 0.0 {
                            v += psi * x[sb + i];
                        }
                    }
                    for k in 0..ndim {
                        du[i][k] += g[ia][k] * v;
                    }
                }
            }
            // Engineering strains in Code_Aster's order: xx yy zz xy (xz yz).
            let mut eps = [0.0; 6];
            for i in 0..ndim {
                eps[i] = du[i][i];
            }
            eps[3] = du[0][1] + du[1][0];
            if ndim == 3 {
                eps[4] = du[0][2] + du[2][0];
                eps[5] = du[1][2] + du[2][1];
            }
            for r in d.iter().take(nsig) {
                vals.push((0..nsig).map(|q| r[q] * eps[q]).sum::<f64>());
            }
        }
        cells[c] = Some(vals);
    }
    let components = md.sigma_names().iter().map(|n| n.to_string()).collect();
    Ok(Field::Elga { components, cells })
}

/// What the conditions of the first instant told, for the run log.
#[derive(Default)]
pub struct FirstConditions {
    pub hm_report: String,
    pub pinned: Vec<String>,
}
