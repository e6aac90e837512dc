//! Profiles of one state's contact pressure along the grid's x and y axes through the
//! contact's centre, as a [`LineChart`]: jkrbem's element values as markers (one colour per
//! axis) and, where the caller hands one in (JKR's for a sphere), a closed-form pressure at the
//! state's own contact radius and approach drawn along the same lines. The edge's tension singularity would stretch the y axis
//! until the interior is flat: the axis is clipped at the heat map's colour scale (the 98th
//! percentile of the interior's |p|, [`pressure_chart`](super::pressure_chart)), the closed
//! form is drawn only where it lies inside, element values beyond are drawn at the limit in a
//! colour of their own, and the title says so.

use super::figure::FigureFormats;
use super::line_chart::{LineChart, Style};
use super::pressure_chart::{colour_scale, contact_box, window};
use super::OutputError;
use crate::analysis::fields::StateFields;
use crate::text::compact_digits;
use std::path::Path;

/// The x axis' description.
pub const X_LABEL: &str = "position along x or y (length, the run's unit)";

/// The y axis' description.
pub const Y_LABEL: &str = "pressure p (force/length², p < 0 tensile)";

/// Points of the closed form's line across the contact.
const LINE_POINTS: usize = 201;

/// The colour of the closed form's line (black).
const CLOSED_FORM_COLOUR: usize = 4;

/// The colour of the element values beyond the clip (vermillion).
const BEYOND_COLOUR: usize = 5;

/// A closed form of the pressure drawn beside the profiles, handed in by the caller (this
/// module computes none): its name and `pressure(r, a, d)` (force/length²) at distance `r`
/// from the apex for the state of mean contact radius `a` and approach `d` (lengths).
#[derive(Clone, Copy)]
pub struct ClosedFormPressure<'a> {
    /// The closed form's name in the legend ("JKR").
    pub name: &'a str,
    /// p(r, a, d) (force/length²).
    pub pressure: &'a dyn Fn(f64, f64, f64) -> f64,
}

/// One axis' profile: the element values along a grid row (x) or column (y).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// "x" or "y": the axis the profile runs along.
    pub axis: &'static str,
    /// The other coordinate of the row or column (length): y for the x profile, x for the y
    /// profile.
    pub offset: f64,
    /// (position along the axis (length), p (force/length²)) of each element in the window
    /// around the contact, in order.
    pub points: Vec<(f64, f64)>,
}

/// The x and y profiles of `f`: the element row and column nearest the centre of the
/// contact's bounding box (the grid's centre where there is no contact), over the heat map's
/// window (the box and a 15 % border).
pub fn profiles(f: &StateFields) -> [Profile; 2] {
    let (i0, i1, j0, j1) = contact_box(f).unwrap_or((0, f.nx, 0, f.ny));
    let nearest = |v: &[f64], lo: usize, hi: usize| {
        let centre = 0.5 * (v[lo] + v[hi - 1]);
        (lo..hi)
            .min_by(|&a, &b| (v[a] - centre).abs().total_cmp(&(v[b] - centre).abs()))
            .unwrap_or(lo)
    };
    let (ic, jc) = (nearest(&f.x, i0, i1), nearest(&f.y, j0, j1));
    let (wi0, wi1, wj0, wj1) = window(f);
    let p = |i: usize, j: usize| f.pressure[j * f.nx + i];
    [
        Profile {
            axis: "x",
            offset: f.y[jc],
            points: (wi0..wi1).map(|i| (f.x[i], p(i, jc))).collect(),
        },
        Profile {
            axis: "y",
            offset: f.x[ic],
            points: (wj0..wj1).map(|j| (f.y[j], p(ic, j))).collect(),
        },
    ]
}

/// The closed form `p(s)` along a line across the contact, s ∈ (−half, half) (length), where
/// |p| ≤ `limit`: the stretch around s = 0 (or the longest one, where the centre lies beyond),
/// ended where the line crosses the limit; and whether any of the line was left out.
fn clipped_line(p: &dyn Fn(f64) -> f64, half: f64, limit: f64) -> (Vec<(f64, f64)>, bool) {
    if half.is_nan() || half <= 0.0 {
        return (Vec::new(), false);
    }
    let n = LINE_POINTS;
    // Open ends: the closed form diverges at the edge.
    let s: Vec<f64> = (0..n)
        .map(|k| half * (2.0 * (k as f64 + 0.5) / n as f64 - 1.0))
        .collect();
    let inside = |v: f64| v.is_finite() && v.abs() <= limit;
    let ok: Vec<bool> = s.iter().map(|&s| inside(p(s))).collect();
    // The runs of samples inside, and the one to draw.
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut k = 0;
    while k < n {
        if ok[k] {
            let start = k;
            while k < n && ok[k] {
                k += 1;
            }
            runs.push((start, k));
        } else {
            k += 1;
        }
    }
    let centre = n / 2;
    let Some(&(lo, hi)) = runs
        .iter()
        .find(|(lo, hi)| (*lo..*hi).contains(&centre))
        .or_else(|| runs.iter().max_by_key(|(lo, hi)| hi - lo))
    else {
        return (Vec::new(), true);
    };
    // Where the line leaves the range between a sample inside and one beyond (bisection).
    let crossing = |a: f64, b: f64| {
        let (mut a, mut b) = (a, b);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if inside(p(m)) {
                a = m;
            } else {
                b = m;
            }
        }
        let v = p(a);
        (a, v.clamp(-limit, limit))
    };
    let mut line = Vec::with_capacity(hi - lo + 2);
    if lo > 0 {
        line.push(crossing(s[lo], s[lo - 1]));
    }
    line.extend((lo..hi).map(|k| (s[k], p(s[k]))));
    if hi < n {
        line.push(crossing(s[hi - 1], s[hi]));
    }
    (line, lo > 0 || hi < n)
}

/// The profile chart of `f`, titled `title` (a note of the clip is added where anything is
/// clipped): the x and y profiles ([`profiles`]) as markers, filled in colour 0 and hollow in
/// colour 1, element values beyond the clip in a colour of their own at the limit, and where
/// `closed` is given its pressure at the state's own mean contact radius and approach along
/// the same lines (one black line where both lines lie as far from the apex, else one per axis
/// in its markers' colour).
pub fn profile_chart(
    f: &StateFields,
    closed: Option<ClosedFormPressure<'_>>,
    title: &str,
) -> LineChart {
    let (limit, _) = colour_scale(f);
    let num = |v: f64| compact_digits(v, 3).replace('-', "−");
    let mut chart = LineChart::new(title, X_LABEL, Y_LABEL);
    let mut clipped = false;
    let [px, py] = profiles(f);
    // x filled, y hollow: where the two coincide (a sphere's), both stay visible.
    for (colour, profile) in [&px, &py].into_iter().enumerate() {
        let style = [Style::Markers, Style::Hollow][colour];
        let other = if profile.axis == "x" { "y" } else { "x" };
        let (within, beyond): (Vec<_>, Vec<_>) =
            profile.points.iter().partition(|(_, p)| p.abs() <= limit);
        clipped |= !beyond.is_empty();
        chart.push(
            &format!(
                "jkrbem along {} ({other} = {})",
                profile.axis,
                num(profile.offset)
            ),
            within,
            colour,
            style,
        );
        if !beyond.is_empty() {
            chart.push(
                &format!(
                    "along {}, beyond the clip (at ±{})",
                    profile.axis,
                    num(limit)
                ),
                beyond
                    .into_iter()
                    .map(|(s, p)| (s, p.clamp(-limit, limit)))
                    .collect(),
                BEYOND_COLOUR,
                style,
            );
        }
    }
    if let Some(closed) = closed {
        let (a, d) = (f.state.mean_radius, f.state.d);
        let name = closed.name;
        let same = (px.offset.abs() - py.offset.abs()).abs() <= 1e-9 * f.dx;
        let lines: Vec<(&Profile, String, usize)> = if same {
            let label = format!("{name} at a = {}, d = {}", num(a), num(d));
            vec![(&px, label, CLOSED_FORM_COLOUR)]
        } else {
            [&px, &py]
                .into_iter()
                .enumerate()
                .map(|(k, pr)| (pr, format!("{name} along {} (a = {})", pr.axis, num(a)), k))
                .collect()
        };
        for (profile, label, colour) in lines {
            let offset = profile.offset;
            let p = |s: f64| (closed.pressure)(s.hypot(offset), a, d);
            let half = ((a - offset.abs()) * (a + offset.abs())).max(0.0).sqrt();
            let (line, cut) = clipped_line(&p, half, limit);
            clipped |= cut;
            chart.push(&label, line, colour, Style::Line);
        }
    }
    if clipped {
        chart.title = format!("{title}; |p| clipped at {}", num(limit));
    }
    chart
}

/// Write [`profile_chart`] to `path` (its SVG path) in each of `formats`, and the points it
/// draws to `<stem>.plot.csv`.
pub fn write_profile_chart(
    path: &Path,
    f: &StateFields,
    closed: Option<ClosedFormPressure<'_>>,
    title: &str,
    formats: FigureFormats,
) -> Result<(), OutputError> {
    profile_chart(f, closed, title).write_figure(path, formats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::jkr_sphere::JkrSphere;
    use crate::scene::{Indenter, Scene};
    use crate::solver::State;

    /// `jkr`'s pressure as the chart takes it.
    fn drawn(jkr: &JkrSphere) -> impl Fn(f64, f64, f64) -> f64 + '_ {
        move |r, a, d| jkr.pressure(r, a, d)
    }

    /// The fields of JKR's pressure for a sphere of R = E* = 1 at contact radius `a` and
    /// approach `d`, on an n × n grid of side Δx = 4a/n with the apex at an element corner.
    fn jkr_fields(n: usize, a: f64, d: f64) -> StateFields {
        let dx = 4.0 * a / n as f64;
        let x: Vec<f64> = (0..n)
            .map(|i| (i as f64 + 0.5 - n as f64 / 2.0) * dx)
            .collect();
        let sphere = JkrSphere {
            radius: 1.0,
            e_star: 1.0,
        };
        let mut pressure = Vec::new();
        let mut contact = Vec::new();
        for &y in &x {
            for &xi in &x {
                let r = xi.hypot(y);
                contact.push(r < a);
                pressure.push(if r < a { sphere.pressure(r, a, d) } else { 0.0 });
            }
        }
        StateFields {
            index: 0,
            label: "force minimum".into(),
            state: State {
                mean_radius: a,
                d,
                ..State::default()
            },
            nx: n,
            ny: n,
            dx,
            x: x.clone(),
            y: x,
            gap: vec![0.0; n * n],
            pressure,
            contact,
            sigma_c: 1.0,
        }
    }

    /// A sphere of R = 1 with a little roughness: no closed form.
    fn rough_sphere() -> Scene {
        use crate::scene::roughness::{generate, RoughnessParams};
        use crate::scene::RoughShape;
        let params = RoughnessParams {
            cutoff: Some(0.2),
            seed: 1,
            ..RoughnessParams::with_rms_slope(64, 0.025, 0.8, 0.05)
        };
        let base = Indenter::ellipsoid(1.0, 1.0);
        let rough = RoughShape::new(base, generate(&params).unwrap(), "generated").unwrap();
        Scene::with_indenter(Indenter::Rough(std::sync::Arc::new(rough)), 1.0, 1.0).unwrap()
    }

    fn sphere(r1: f64, r2: f64) -> Scene {
        Scene::new(r1, r2, 1.0, 1.0).unwrap()
    }

    #[test]
    fn the_closed_form_is_drawn_for_the_sphere_alone() {
        let f = jkr_fields(64, 0.8, 0.3);
        let scenes = [
            (sphere(1.0, 1.0), true),
            (sphere(3.0, 1.0), false),
            (
                Scene::with_indenter(Indenter::power_law(2.0, 0.5), 1.0, 1.0).unwrap(),
                true,
            ),
            (
                Scene::with_indenter(Indenter::power_law(3.0, 0.5), 1.0, 1.0).unwrap(),
                false,
            ),
            (
                Scene::with_indenter(Indenter::flat_punch(1.0), 1.0, 1.0).unwrap(),
                false,
            ),
            (rough_sphere(), false),
        ];
        for (scene, has) in scenes {
            let jkr = JkrSphere::of(&scene);
            assert_eq!(jkr.is_some(), has, "{}", scene.headline());
            let p = jkr.as_ref().map(drawn);
            let closed = p.as_ref().map(|p| ClosedFormPressure {
                name: "JKR",
                pressure: p,
            });
            let chart = profile_chart(&f, closed, "t");
            let lines = chart
                .curves
                .iter()
                .filter(|c| c.style == Style::Line)
                .count();
            assert_eq!(lines, usize::from(has), "{}", scene.headline());
            let markers: Vec<&str> = chart
                .curves
                .iter()
                .filter(|c| c.style != Style::Line && c.color < 2)
                .map(|c| c.label.as_str())
                .collect();
            assert_eq!(markers.len(), 2, "{markers:?}");
            // Drawn where the crate draws charts (the `figures` feature).
            assert_eq!(chart.to_svg().is_ok(), cfg!(feature = "figures"));
        }
        // R = 1/(2s) for the power law of n = 2.
        let pl = Scene::with_indenter(Indenter::power_law(2.0, 0.25), 3.0, 1.0);
        assert_eq!(
            JkrSphere::of(&pl.unwrap()),
            Some(JkrSphere {
                radius: 2.0,
                e_star: 3.0
            })
        );
    }

    #[test]
    fn the_line_and_the_axis_are_clipped_at_the_interior_s_scale() {
        // The edge's singularity: without the clip the line would reach −∞.
        let (a, d) = (0.8, 0.3);
        let f = jkr_fields(64, a, d);
        let (limit, peak) = colour_scale(&f);
        assert!(peak > limit, "the edge lies beyond the interior's scale");
        let jkr = JkrSphere::of(&sphere(1.0, 1.0)).unwrap();
        let p = drawn(&jkr);
        let closed = ClosedFormPressure {
            name: "JKR",
            pressure: &p,
        };
        let chart = profile_chart(&f, Some(closed), "t");
        assert!(chart.title.contains("clipped"), "{}", chart.title);
        for c in &chart.curves {
            for (s, p) in &c.points {
                assert!(p.abs() <= limit * (1.0 + 1e-12), "{}: ({s}, {p})", c.label);
            }
        }
        // The line ends at the limit, where JKR's pressure crosses it.
        let line = &chart
            .curves
            .iter()
            .find(|c| c.style == Style::Line)
            .unwrap();
        let (s, p) = *line.points.last().unwrap();
        assert!((p.abs() - limit).abs() < 1e-9 * limit, "{p} vs {limit}");
        assert!(s > 0.5 * a && s < a, "{s}");
        // Their own markers hold the element values beyond the clip, at the limit.
        let beyond: Vec<f64> = chart
            .curves
            .iter()
            .filter(|c| c.color == BEYOND_COLOUR)
            .flat_map(|c| c.points.iter().map(|p| p.1))
            .collect();
        assert!(beyond.len() >= 2, "{beyond:?}");
        assert!(beyond
            .iter()
            .all(|p| (p.abs() - limit).abs() < 1e-12 * limit));
        // The markers are the grid's values: on the row next to the apex (y = ±Δx/2).
        let [px, py] = profiles(&f);
        assert!(
            (px.offset.abs() - 0.5 * f.dx).abs() < 1e-12,
            "{}",
            px.offset
        );
        assert_eq!(px.points.len(), py.points.len());
    }
}
