//! What a person sees while a run goes: a progress line on stderr (when it is a terminal),
//! the notes and the warnings.

use indicatif::{ProgressBar, ProgressStyle};
use jkrbem::model::Model;
use jkrbem::run::Watch;
use jkrbem::solver::{Phase, State};
use std::io::IsTerminal;
use std::sync::Mutex;

/// The progress line's layout: elapsed time, a bar of the load steps, the fraction done and
/// the estimated time left, then [`progress_message`].
pub const PROGRESS_TEMPLATE: &str = "[{elapsed_precise}] {bar:20} {percent:>3}% ETA {eta} {msg}";

/// The progress line's text for the latest state: the load step of all expected, and where
/// the pull-off is (the bar, percentage and ETA are drawn beside it).
pub fn progress_message(model: &Model, s: &State) -> String {
    let phase = match s.phase {
        Phase::Approach => "approach",
        Phase::Pulloff => "pull-off",
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

/// A [`Watch`] for a person: notes and warnings on stderr, and a progress bar of each
/// pull-off's load steps when stderr is a terminal.
#[derive(Default)]
pub struct Progress {
    bar: Mutex<Option<ProgressBar>>,
}

impl Progress {
    /// A watch with no bar yet (one is drawn per pull-off).
    pub fn new() -> Self {
        Self::default()
    }
}

impl Watch for Progress {
    fn note(&self, line: &str) {
        errln!("jkrbem: {line}");
    }

    fn pulloff_started(&self, model: &Model) {
        if !std::io::stderr().is_terminal() {
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
        if let Some(pb) = self.bar.lock().ok().as_ref().and_then(|b| b.as_ref()) {
            pb.set_position(s.step as u64);
            pb.set_message(progress_message(model, s));
        }
    }

    fn pulloff_ended(&self) {
        if let Some(pb) = self.bar.lock().ok().and_then(|mut b| b.take()) {
            pb.finish_and_clear();
        }
    }

    fn warning(&self, line: &str) {
        errln!("jkrbem: warning: {line}");
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
        let text = progress_message(&model, &state);
        assert!(text.contains("step 57/200 (onset)"), "{text}");
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
}
