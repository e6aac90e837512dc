//! How often a plain progress line is printed where stderr is not a terminal.

use std::time::{Duration, Instant};

/// Least time between two plain progress lines where stderr is not a terminal.
pub const PLAIN_EVERY: Duration = Duration::from_secs(60);

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
pub fn clock(t: Duration) -> String {
    format!("[{}]", indicatif::FormattedDuration(t))
}

#[cfg(test)]
mod tests {
    use super::*;

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
