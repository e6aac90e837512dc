//! What a person sees while a run goes: a progress line on stderr (a bar redrawn in place
//! when stderr is a terminal; else, as in a log file, a plain line at most once a minute),
//! the notes and the warnings. The line's text is [`message`], the bar's position within a
//! grid [`count`], the pace of plain lines [`throttle`].

mod count;
mod message;
mod throttle;

pub use count::StepCount;
pub use message::{progress_message, PROGRESS_TEMPLATE};
pub use throttle::{Throttle, PLAIN_EVERY};

use indicatif::{ProgressBar, ProgressStyle};
use jkrbem::model::Model;
use jkrbem::session::batch::pool::SceneEnded;
use jkrbem::session::Watch;
use jkrbem::solver::State;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::Instant;

/// A [`Watch`] for a person: notes and warnings on stderr, and the progress of each
/// pull-off's load steps: a bar when stderr is a terminal, else a plain line at most every
/// [`PLAIN_EVERY`].
#[derive(Default)]
pub struct Progress {
    /// The running pull-off's count, and its bar where stderr is a terminal.
    grid: Mutex<Option<Grid>>,
    plain: Mutex<Option<Throttle>>,
}

/// One grid's pull-off as the progress line follows it.
struct Grid {
    count: StepCount,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A watch with no bar yet (one is drawn per pull-off).
    pub fn new() -> Self {
        Self::default()
    }

    /// Show `s`, found by the pull-off of `model` (`held`: held back, see [`progress_message`]).
    fn show(&self, model: &Model, s: &State, held: bool) {
        let Ok(mut grid) = self.grid.lock() else {
            return;
        };
        let Some(grid) = grid.as_mut() else {
            return;
        };
        grid.count.advance(s.step);
        let text = progress_message(model, s, held, &grid.count);
        if let Some(pb) = &grid.bar {
            // Length first: the position never passes it.
            pb.set_length(grid.count.length());
            pb.set_position(grid.count.position());
            pb.set_message(text);
            return;
        }
        let due = self
            .plain
            .lock()
            .ok()
            .and_then(|mut t| t.as_mut().and_then(|t| t.due(Instant::now())));
        if let Some(elapsed) = due {
            errln!("jkrbem: {} {text}", throttle::clock(elapsed));
        }
    }
}

impl Watch for Progress {
    fn note(&self, line: &str) {
        errln!("jkrbem: {line}");
    }

    fn pulloff_started(&self, model: &Model) {
        let expected = model.expected_steps();
        let bar = if std::io::stderr().is_terminal() {
            let pb = ProgressBar::new(StepCount::new(expected).length());
            pb.set_style(
                ProgressStyle::with_template(PROGRESS_TEMPLATE)
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            Some(pb)
        } else {
            if let Ok(mut plain) = self.plain.lock() {
                // One throttle for the whole command: a line at most once a period.
                plain.get_or_insert_with(|| Throttle::new(PLAIN_EVERY, Instant::now()));
            }
            None
        };
        // Each grid starts afresh: its own count from step 0, its own bar.
        if let Ok(mut grid) = self.grid.lock() {
            if let Some(old) = grid.take().and_then(|g| g.bar) {
                old.finish_and_clear();
            }
            *grid = Some(Grid {
                count: StepCount::new(expected),
                bar,
            });
        }
    }

    fn state(&self, model: &Model, s: &State) {
        self.show(model, s, false);
    }

    fn state_held(&self, model: &Model, s: &State) {
        self.show(model, s, true);
    }

    fn pulloff_ended(&self) {
        if let Some(pb) = self
            .grid
            .lock()
            .ok()
            .and_then(|mut g| g.take())
            .and_then(|g| g.bar)
        {
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
mod tests;
