//! Where one grid's progress bar stands: the load steps counted against the steps expected,
//! an estimate that onsets, the search near the minimum and a late end of contact can pass.

/// The bar's position and length within one grid's pull-off: the position is the furthest load
/// step seen (an onset found on going back does not move it back), and the length grows to the
/// position once the count passes the estimate, so that the position never exceeds it. A new
/// grid starts a new count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepCount {
    /// The load steps expected at the start (at least 1).
    expected: u64,
    /// The bar's length: the expected steps, or the furthest step past them.
    length: u64,
    /// The furthest load step seen.
    position: u64,
}

impl StepCount {
    /// A count at step 0 of `expected` steps.
    pub fn new(expected: usize) -> Self {
        let expected = (expected as u64).max(1);
        StepCount {
            expected,
            length: expected,
            position: 0,
        }
    }

    /// Count a state of load step `step`.
    pub fn advance(&mut self, step: usize) {
        self.position = self.position.max(step as u64);
        self.length = self.length.max(self.position);
    }

    /// The bar's position (≤ [`StepCount::length`]).
    pub fn position(&self) -> u64 {
        self.position
    }

    /// The bar's length.
    pub fn length(&self) -> u64 {
        self.length
    }

    /// A state's step against the count: "57/200", or "203, past the 200 expected" once the
    /// count has passed the estimate.
    pub fn text(&self, step: usize) -> String {
        if self.length > self.expected {
            format!("{step}, past the {} expected", self.expected)
        } else {
            format!("{step}/{}", self.expected)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_position_never_passes_the_length_nor_goes_back() {
        // Before: "step 203/200", and the bar went back with each onset found on going back.
        let mut c = StepCount::new(200);
        let mut last = 0;
        for step in [1, 2, 57, 60, 58, 59, 61, 199, 200, 203, 201, 210] {
            c.advance(step);
            assert!(c.position() <= c.length(), "{c:?}");
            assert!(c.position() >= last, "went back at {step}: {c:?}");
            last = c.position();
        }
        assert_eq!((c.position(), c.length()), (210, 210));
        assert_eq!(c.text(210), "210, past the 200 expected");
        assert_eq!(c.text(205), "205, past the 200 expected");
    }

    #[test]
    fn within_the_estimate_the_length_is_the_expected_steps() {
        let mut c = StepCount::new(200);
        c.advance(60);
        c.advance(57);
        assert_eq!((c.position(), c.length()), (60, 200));
        assert_eq!(c.text(57), "57/200");
        // A new grid starts from 0 again, with its own estimate.
        let fresh = StepCount::new(150);
        assert_eq!((fresh.position(), fresh.length()), (0, 150));
        // No expected step at all still gives a bar of length 1.
        let mut one = StepCount::new(0);
        assert_eq!(one.length(), 1);
        one.advance(1);
        assert_eq!((one.position(), one.length()), (1, 1));
    }
}
