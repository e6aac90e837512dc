//! The progress line's text: where the pull-off is, beside the bar.

use super::count::StepCount;
use jkrbem::model::Model;
use jkrbem::solver::{Phase, State};

/// The progress line's layout: elapsed time, a bar of the load steps, the fraction done and
/// the estimated time left, then [`progress_message`].
pub const PROGRESS_TEMPLATE: &str = "[{elapsed_precise}] {bar:20} {percent:>3}% ETA {eta} {msg}";

/// The progress line's text for the latest state: its load step against the grid's `count`,
/// and where the pull-off is (the bar, percentage and ETA are drawn beside it). An onset
/// `held` back was located by the search for the force minimum, which goes back to earlier
/// steps.
pub fn progress_message(model: &Model, s: &State, held: bool, count: &StepCount) -> String {
    let phase = match s.phase {
        Phase::Approach => "approach",
        Phase::Pulloff => "pull-off",
        Phase::Onset if held => "onset, searching near the minimum",
        Phase::Onset => "onset",
        Phase::Regrid => "re-grid",
        Phase::Loading => "loading",
        Phase::LoadingJump => "loading, a jump",
        Phase::Jump => "jump",
    };
    format!(
        "{}, step {} ({phase}): d̄ = {}, F̄ = {}, c̄ = {}",
        progress_scene(&model.scene),
        count.text(s.step),
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
