//! What a study writes: the CSV of every run, a markdown table, and log–log plots of an error against
//! the wall time and against the unknowns, one curve per knob (the other knobs fixed), the Pareto front
//! marked.

use super::measure::Metrics;
use super::Run;
use super::Study;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// The value of an error metric of a run: a POST_ERREUR key, or `check` (the largest relative error of
/// the ANALYTIQUE / SOURCE_EXTERNE lines).
pub fn error_of(m: &Metrics, key: &str) -> Option<f64> {
    if key == "check" {
        m.check_max
    } else if key.starts_with("check:") {
        m.check_by_legend.get(key).copied()
    } else {
        m.errors.get(key).copied()
    }
}

/// The time a run spent computing: its wall time less the time POST_ERREUR took to measure its error
/// (the reference formulas are interpreted at every integration point, which can cost more than the
/// solve itself and is not part of what the accuracy costs).
pub fn cost(m: &Metrics) -> f64 {
    m.wall - m.stages.get("POST_ERREUR").copied().unwrap_or(0.0)
}

/// Did the run stop (an error, a time-out) rather than finish, whatever its checks said? Studies expect
/// NON_REGRESSION lines to fail away from the variant their values were recorded for.
pub fn stopped(m: &Metrics) -> bool {
    m.diagnostic.starts_with("<F>") || m.diagnostic == "TIMEOUT"
}

/// The cost axes of the plots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Axis {
    Wall,
    Unknowns,
}

impl Axis {
    pub fn of(self, m: &Metrics) -> Option<f64> {
        match self {
            Axis::Wall => Some(cost(m)),
            Axis::Unknowns => m.unknowns.map(|u| u as f64),
        }
    }
    fn label(self) -> &'static str {
        match self {
            Axis::Wall => "wall time without POST_ERREUR (s)",
            Axis::Unknowns => "unknowns",
        }
    }
    fn tag(self) -> &'static str {
        match self {
            Axis::Wall => "time",
            Axis::Unknowns => "unknowns",
        }
    }
}

/// The runs on the Pareto front of (cost, error): no other run is both cheaper and more accurate (by
/// more than 1e-6 relative).
/// Runs without both values are left out. Returned in increasing cost.
pub fn pareto(runs: &[Run], key: &str, axis: Axis) -> Vec<usize> {
    let mut pts: Vec<(usize, f64, f64)> = runs
        .iter()
        .enumerate()
        .filter(|(_, r)| !stopped(&r.metrics))
        .filter_map(|(i, r)| Some((i, axis.of(&r.metrics)?, error_of(&r.metrics, key)?)))
        .filter(|(_, x, y)| x.is_finite() && y.is_finite())
        .collect();
    pts.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.2.total_cmp(&b.2)));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    // A run whose error is the best one's to 1e-6 (round-off of a tighter tolerance) does not improve it.
    for (i, _, y) in pts {
        if y < best * (1.0 - 1e-6) {
            front.push(i);
            best = y;
        }
    }
    front
}

/// The error metrics present in the runs: POST_ERREUR keys in order of first appearance, then `check`.
pub fn error_keys(runs: &[Run]) -> Vec<String> {
    let mut keys: Vec<String> = Vec::new();
    for r in runs {
        for k in r.metrics.errors.keys() {
            if !keys.contains(k) {
                keys.push(k.clone());
            }
        }
    }
    if runs.iter().any(|r| r.metrics.check_max.is_some()) {
        keys.push("check".into());
    }
    // Per legend, when the check lines have more than one.
    let mut legends: Vec<String> = Vec::new();
    for r in runs {
        for k in r.metrics.check_by_legend.keys() {
            if !legends.contains(k) {
                legends.push(k.clone());
            }
        }
    }
    if legends.len() > 1 {
        keys.extend(legends);
    }
    keys
}

fn opt(v: Option<f64>, f: impl Fn(f64) -> String) -> String {
    v.map(f).unwrap_or_default()
}

/// One row per run: the knob values, diagnostic, wall time, peak memory, unknowns, Newton iterations,
/// the time of every command, every error metric, and whether the run is on the Pareto front of the
/// first error metric against time.
pub fn csv(s: &Study) -> String {
    let keys = error_keys(&s.runs);
    let mut stages: Vec<String> = Vec::new();
    for r in &s.runs {
        for k in r.metrics.stages.keys() {
            if !stages.contains(k) {
                stages.push(k.clone());
            }
        }
    }
    let front = keys.first().map(|k| pareto(&s.runs, k, Axis::Wall)).unwrap_or_default();
    let mut out = String::new();
    let mut head: Vec<String> = vec!["run".into()];
    head.extend(s.knobs.iter().map(|k| k.name.clone()));
    head.extend(
        ["diagnostic", "wall_s", "cost_s", "peak_mib", "unknowns", "newton_iters"].iter().map(|s| s.to_string()),
    );
    head.extend(stages.iter().map(|n| format!("t_{n}")));
    head.extend(keys.iter().map(|k| format!("err_{k}")));
    head.extend(["checks", "nook", "pareto_time"].iter().map(|s| s.to_string()));
    out.push_str(&head.join(","));
    out.push('\n');
    for (i, r) in s.runs.iter().enumerate() {
        let m = &r.metrics;
        let mut row: Vec<String> = vec![r.label.clone()];
        row.extend(r.values.iter().map(|v| csv_field(v)));
        row.push(m.diagnostic.clone());
        row.push(format!("{:.4}", m.wall));
        row.push(format!("{:.4}", cost(m)));
        row.push(format!("{:.1}", m.peak_mib));
        row.push(m.unknowns.map(|u| u.to_string()).unwrap_or_default());
        row.push(m.newton.map(|u| u.to_string()).unwrap_or_default());
        for st in &stages {
            row.push(opt(m.stages.get(st).copied(), |v| format!("{v:.4}")));
        }
        for k in &keys {
            row.push(opt(error_of(m, k), |v| format!("{v:.6e}")));
        }
        row.push(m.checks.to_string());
        row.push(m.nook.to_string());
        row.push(if front.contains(&i) { "1".into() } else { "0".into() });
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

fn csv_field(v: &str) -> String {
    if v.contains(',') || v.contains('"') {
        format!("\"{}\"", v.replace('"', "\"\""))
    } else {
        v.to_string()
    }
}

/// A markdown table of the runs: knobs, unknowns, Newton iterations, wall time (with and without
/// POST_ERREUR), peak memory, the costliest command (POST_ERREUR aside), every error metric, and the
/// Pareto front (against time) of the first one; a run that stopped says so.
pub fn markdown(s: &Study) -> String {
    let keys = error_keys(&s.runs);
    let front = keys.first().map(|k| pareto(&s.runs, k, Axis::Wall)).unwrap_or_default();
    let mut out = String::new();
    let mut head: Vec<String> = s.knobs.iter().map(|k| k.name.clone()).collect();
    head.extend(
        ["unknowns", "Newton", "wall (s)", "less POST_ERREUR (s)", "peak (MiB)", "costliest command (s)"]
            .iter()
            .map(|s| s.to_string()),
    );
    head.extend(keys.iter().map(|k| if k == "check" { "largest check error".into() } else { k.clone() }));
    head.push(format!("Pareto ({})", keys.first().map(String::as_str).unwrap_or("-")));
    let _ = writeln!(out, "| {} |", head.join(" | "));
    let align: Vec<&str> =
        head.iter().enumerate().map(|(i, _)| if i < s.knobs.len() { "---" } else { "---:" }).collect();
    let _ = writeln!(out, "|{}|", align.join("|"));
    for (i, r) in s.runs.iter().enumerate() {
        let m = &r.metrics;
        let mut row: Vec<String> = r.values.clone();
        row.push(m.unknowns.map(|u| u.to_string()).unwrap_or("-".into()));
        row.push(m.newton.map(|u| u.to_string()).unwrap_or("-".into()));
        row.push(if m.diagnostic == "TIMEOUT" { "timeout".into() } else { format!("{:.3}", m.wall) });
        row.push(format!("{:.3}", cost(m)));
        row.push(format!("{:.0}", m.peak_mib));
        let top = m.stages.iter().filter(|(n, _)| *n != "POST_ERREUR").max_by(|a, b| a.1.total_cmp(b.1));
        row.push(top.map(|(n, v)| format!("{n} {v:.3}")).unwrap_or("-".into()));
        for k in &keys {
            row.push(opt(error_of(m, k), |v| format!("{v:.2e}")));
        }
        row.push(if front.contains(&i) { "◆".into() } else { String::new() });
        if stopped(m) {
            let last = row.len() - 1;
            row[last] = format!("{} {}", row[last], m.diagnostic).trim().to_string();
        }
        let _ = writeln!(out, "| {} |", row.join(" | "));
    }
    out
}

/// The Pareto front of every error metric against time, run by run: which variants buy accuracy for the
/// least time.
pub fn pareto_summary(s: &Study) -> String {
    let mut out = String::new();
    for key in error_keys(&s.runs) {
        let front = pareto(&s.runs, &key, Axis::Wall);
        let steps: Vec<String> = front
            .iter()
            .map(|&i| {
                let r = &s.runs[i];
                let e = error_of(&r.metrics, &key).unwrap_or(f64::NAN);
                format!("{} ({:.3} s, {e:.2e})", super::describe(&s.knobs, &r.values), cost(&r.metrics))
            })
            .collect();
        let _ = writeln!(out, "Pareto front of {key} against time: {}", steps.join(" → "));
    }
    out
}

/// One log–log plot of `key` against `axis` as an SVG file.
pub fn plot(s: &Study, key: &str, axis: Axis, path: &Path) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let point = |r: &Run| -> Option<(f64, f64)> {
        let (x, y) = (axis.of(&r.metrics)?, error_of(&r.metrics, key)?);
        (x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite() && !stopped(&r.metrics)).then_some((x, y))
    };
    let pts: Vec<(f64, f64)> = s.runs.iter().filter_map(point).collect();
    if pts.is_empty() {
        return Err(format!("{}: no run has a positive {key} and {}", path.display(), axis.label()));
    }
    let bounds = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(0.0, f64::max);
        (lo / 1.6, hi * 1.6)
    };
    let (x0, x1) = bounds(pts.iter().map(|p| p.0).collect());
    let (y0, y1) = bounds(pts.iter().map(|p| p.1).collect());
    let root = SVGBackend::new(path, (760, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let title =
        format!("{}: {} against {}", s.title, if key == "check" { "largest check error" } else { key }, axis.label());
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(axis.label())
        .y_desc(if key == "check" { "largest relative check error".to_string() } else { format!("{key} (relative)") })
        .y_label_formatter(&|v| nice_label(*v))
        .x_label_formatter(&|v| nice_label(*v))
        .draw()
        .map_err(|e| err(&e))?;
    // The Pareto front, under the curves.
    let front: Vec<(f64, f64)> = pareto(&s.runs, key, axis).iter().filter_map(|&i| point(&s.runs[i])).collect();
    let grey = RGBColor(170, 170, 170);
    chart
        .draw_series(LineSeries::new(front.clone(), grey.stroke_width(6)))
        .map_err(|e| err(&e))?
        .label("Pareto front")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], grey.stroke_width(6)));
    chart.draw_series(front.iter().map(|p| Circle::new(*p, 8, BLACK.stroke_width(1)))).map_err(|e| err(&e))?;
    // One curve per knob: the runs that differ only by that knob's value, in the order of its values.
    let mut colour = 0;
    for (k, knob) in s.knobs.iter().enumerate() {
        if !s.curves.contains(&knob.name) {
            continue;
        }
        // (the other knobs' values, [(position of this knob's value, point)]).
        type Curve = (Vec<String>, Vec<(usize, (f64, f64))>);
        let mut groups: Vec<Curve> = Vec::new();
        for r in &s.runs {
            let Some(p) = point(r) else { continue };
            let others: Vec<String> =
                r.values.iter().enumerate().filter(|(j, _)| *j != k).map(|(_, v)| v.clone()).collect();
            let pos = knob.values.iter().position(|v| *v == r.values[k]).unwrap_or(0);
            match groups.iter_mut().find(|g| g.0 == others) {
                Some(g) => g.1.push((pos, p)),
                None => groups.push((others, vec![(pos, p)])),
            }
        }
        for (others, mut line) in groups {
            if line.len() < 2 {
                continue;
            }
            line.sort_by_key(|(pos, _)| *pos);
            let c = Palette99::pick(colour).to_rgba();
            colour += 1;
            let fixed: Vec<String> = s
                .knobs
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != k)
                .zip(&others)
                .map(|((_, kn), v)| format!("{}={v}", kn.name))
                .collect();
            let label = if fixed.is_empty() {
                format!("{} = {} … {}", knob.name, knob.values[0], knob.values[knob.values.len() - 1])
            } else {
                format!("{} varies ({})", knob.name, fixed.join(", "))
            };
            let xy: Vec<(f64, f64)> = line.iter().map(|(_, p)| *p).collect();
            chart
                .draw_series(LineSeries::new(xy.clone(), c.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
            chart.draw_series(xy.iter().map(|p| Circle::new(*p, 3, c.filled()))).map_err(|e| err(&e))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// An axis label at 1, 2 and 5 times a power of ten (the others left blank: a log axis has many ticks).
fn nice_label(v: f64) -> String {
    if v.is_nan() || v <= 0.0 {
        return String::new();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    if ![1.0, 2.0, 5.0].iter().any(|n| (m - n).abs() < 1e-6) {
        return String::new();
    }
    if (-2.0..4.0).contains(&e) {
        let digits = if e < 0.0 { (-e) as usize } else { 0 };
        format!("{v:.digits$}")
    } else {
        format!("{m:.0}e{e:.0}")
    }
}

/// The plot files of a study: `<key>_vs_time.svg` and `<key>_vs_unknowns.svg` per error metric.
pub fn plot_name(key: &str, axis: Axis) -> String {
    let k: String = key.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    format!("{k}_vs_{}.svg", axis.tag())
}
