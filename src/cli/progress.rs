//! What a person sees while a run goes: a progress line on stderr (a bar redrawn in place
//! when stderr is a terminal; else, as in a log file, a plain line at most once a minute),
//! the notes and the warnings.

use indicatif::{ProgressBar, ProgressStyle};
use jkrbem::model::Model;
use jkrbem::run::scenes::pool::SceneEnded;
use jkrbem::run::Watch;
use jkrbem::solver::{Phase, State};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Least time between two plain progress lines where stderr is not a terminal.
pub const PLAIN_EVERY: Duration = Duration::from_secs(60);

/// The progress line's layout: elapsed time, a bar of the load steps, the fraction done and
/// the estimated time left, then [`progress_message`].
pub const PROGRESS_TEMPLATE: &str = "[{elapsed_precise}] {bar:20} {percent:>3}% ETA {eta} {msg}";

/// The progress line's text for the latest state: the load step of all expected, and where
/// the pull-off is (the bar, percentage and ETA are drawn beside it). An onset `held` back
/// was located by the search for the force minimum, which goes back to earlier steps.
pub fn progress_message(model: &Model, s: &State, held: bool) -> String {
    let phase = match s.phase {
        Phase::Approach => "approach",
        Phase::Pulloff => "pull-off",
        Phase::Onset if held => "onset, searching near the minimum",
        Phase::Onset => "onset",
        Phase::Regrid => "re-grid",
    };
    format!(
        "{}, step {}/{} ({phase}): d̄ = {}, F̄ = {}, c̄ = {}",
        progress_scene(&model.scene),
        s.step,
        model.expected_steps(),
        jkrbem::text::fixed(s.d_bar, 4),
        jkrbem::text::fixed(s.f_bar, 4),
        jkrbem::text::fixed(s.c_bar, 4)
    )
}

/// "R1/R2 = 5" for an ellipsoid, else the indenter's name.
fn progress_scene(scene: &jkrbem::scene::Scene) -> String {
    if scene.is_ellipsoid() {
        format!("R1/R2 = {}", jkrbem::text::compact(scene.ratio()))
    } else {
        scene.indenter.name().to_string()
    }
}

/// When a plain progress line is due: at most once per `every` since the last one (or
/// since the start).
#[derive(Debug)]
pub struct Throttle {
    every: Duration,
    start: Instant,
    last: Instant,
}

impl Throttle {
    /// A throttle that starts counting at `now`.
    pub fn new(every: Duration, now: Instant) -> Self {
        Throttle {
            every,
            start: now,
            last: now,
        }
    }

    /// The time since the start if a line is due at `now` (it is then counted as given).
    pub fn due(&mut self, now: Instant) -> Option<Duration> {
        if now.saturating_duration_since(self.last) < self.every {
            return None;
        }
        self.last = now;
        Some(now.saturating_duration_since(self.start))
    }
}

/// "[01:02:03]": hours, minutes and seconds, as the bar's elapsed time shows them.
fn clock(t: Duration) -> String {
    format!("[{}]", indicatif::FormattedDuration(t))
}

/// A [`Watch`] for a person: notes and warnings on stderr, and the progress of each
/// pull-off's load steps: a bar when stderr is a terminal, else a plain line at most every
/// [`PLAIN_EVERY`].
#[derive(Default)]
pub struct Progress {
    bar: Mutex<Option<ProgressBar>>,
    plain: Mutex<Option<Throttle>>,
}

impl Progress {
    /// A watch with no bar yet (one is drawn per pull-off).
    pub fn new() -> Self {
        Self::default()
    }

    /// Show `s`, found by the pull-off of `model` (`held`: held back, see [`progress_message`]).
    fn show(&self, model: &Model, s: &State, held: bool) {
        if let Some(pb) = self.bar.lock().ok().as_ref().and_then(|b| b.as_ref()) {
            // An onset found on going back does not move the bar back.
            pb.set_position(pb.position().max(s.step as u64));
            pb.set_message(progress_message(model, s, held));
            return;
        }
        let due = self
            .plain
            .lock()
            .ok()
            .and_then(|mut t| t.as_mut().and_then(|t| t.due(Instant::now())));
        if let Some(elapsed) = due {
            errln!(
                "jkrbem: {} {}",
                clock(elapsed),
                progress_message(model, s, held)
            );
        }
    }
}

impl Watch for Progress {
    fn note(&self, line: &str) {
        errln!("jkrbem: {line}");
    }

    fn pulloff_started(&self, model: &Model) {
        if !std::io::stderr().is_terminal() {
            if let Ok(mut plain) = self.plain.lock() {
                // Concurrent pull-offs (a sweep's) share the one throttle.
                plain.get_or_insert_with(|| Throttle::new(PLAIN_EVERY, Instant::now()));
            }
            return;
        }
        let pb = ProgressBar::new(model.expected_steps() as u64);
        pb.set_style(
            ProgressStyle::with_template(PROGRESS_TEMPLATE)
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        if let Ok(mut bar) = self.bar.lock() {
            *bar = Some(pb);
        }
    }

    fn state(&self, model: &Model, s: &State) {
        self.show(model, s, false);
    }

    fn state_held(&self, model: &Model, s: &State) {
        self.show(model, s, true);
    }

    fn pulloff_ended(&self) {
        if let Some(pb) = self.bar.lock().ok().and_then(|mut b| b.take()) {
            pb.finish_and_clear();
        }
    }

    fn warning(&self, line: &str) {
        errln!("jkrbem: warning: {line}");
    }

    fn scene_ended(&self, s: &SceneEnded) {
        let what = match (s.f_ad_bar, s.grid_f_ad_bar, s.failure) {
            (_, _, Some(why)) => format!("FAILED: {}", why.lines().next().unwrap_or_default()),
            (Some(f), _, None) => format!("|min F̄| = {}", jkrbem::text::fixed(f, 4)),
            (None, Some(f), None) => format!("the grid's |min F̄| = {}", jkrbem::text::fixed(f, 4)),
            (None, None, None) => "no adhesive force (see its summary)".to_string(),
        };
        errln!("jkrbem: {} ({} of {}): {what}", s.label, s.done, s.total);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use jkrbem::model::ModelOptions;
    use jkrbem::scene::Scene;

    #[test]
    fn the_progress_line_shows_the_step_of_all_and_an_eta() {
        // Before: "state 57" (the load step, repeated by its onsets), no fraction, no ETA.
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                steps: 200,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        assert_eq!(model.expected_steps(), 200);
        let state = State {
            step: 57,
            phase: Phase::Onset,
            d: 0.1,
            force: -0.3,
            area: 1.0,
            mean_radius: 1.0,
            a_axis: 1.0,
            b_axis: 1.0,
            n_contact: 100,
            cg_iterations: 5,
            detach_sweeps: 1,
            d_bar: -0.00001,
            f_bar: -0.4321,
            c_bar: 0.9,
            a_bar: 0.9,
            b_bar: 0.9,
            cg_residual: 1e-9,
            dx: 0.1,
        };
        let text = progress_message(&model, &state, false);
        assert!(text.contains("step 57/200 (onset)"), "{text}");
        let held = progress_message(&model, &state, true);
        assert!(
            held.contains("step 57/200 (onset, searching near the minimum)"),
            "{held}"
        );
        assert!(
            text.contains("d̄ = 0.0000") && text.contains("F̄ = -0.4321"),
            "{text}"
        );
        assert!(!text.contains("state"), "{text}");
        for part in ["{bar", "{percent", "{eta}"] {
            assert!(PROGRESS_TEMPLATE.contains(part), "{part}");
        }
        assert!(ProgressStyle::with_template(PROGRESS_TEMPLATE).is_ok());
        // A final approach stops the bar's length early.
        let short = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                steps: 200,
                final_d_bar: Some(0.0),
                ..ModelOptions::default()
            },
        )
        .unwrap();
        assert!(short.expected_steps() < 200);
    }

    #[test]
    fn a_plain_progress_line_is_due_at_most_once_a_period() {
        // Where stderr is not a terminal (a log file), progress is a plain line, not a bar
        // redrawn in place: at most one per period, with the time since the start.
        let t0 = Instant::now();
        let every = Duration::from_secs(60);
        let mut t = Throttle::new(every, t0);
        assert_eq!(t.due(t0), None);
        assert_eq!(t.due(t0 + Duration::from_secs(59)), None);
        assert_eq!(
            t.due(t0 + Duration::from_secs(61)),
            Some(Duration::from_secs(61))
        );
        assert_eq!(t.due(t0 + Duration::from_secs(100)), None);
        assert_eq!(
            t.due(t0 + Duration::from_secs(3725)),
            Some(Duration::from_secs(3725))
        );
        assert_eq!(clock(Duration::from_secs(3725)), "[01:02:05]");
    }
}
