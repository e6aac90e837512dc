//! The pull-off protocol's rules for one element, defined once: the Pohrt–Popov sweep and
//! the fraction of a load step at which an element reaches the detachment stress. The CPU
//! backend applies these functions; a device backend runs the same rule in its kernels
//! (shaders/contact.wgsl, shaders/reduce.wgsl), and the conformance suite holds it to them.
//! The state measurement's definition is [`super::measure::measure_mask`].

/// What one element does in a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flip {
    /// It stays in or out of contact.
    Keep,
    /// It leaves C: its tensile stress exceeds σ_c.
    Detach,
    /// It joins C: its gap is negative.
    Attach,
}

/// The Pohrt–Popov rule for one element: in contact, it detaches when p < −σ_c (p and σ_c
/// stresses, σ_c = 0 the non-adhesive rule); out of contact, it attaches when its gap
/// g = h − d + u (length) is negative, if the sweep attaches (`gap` = `Some`).
pub fn sweep_element(in_contact: bool, p: f64, gap: Option<f64>, sigma_c: f64) -> Flip {
    match (in_contact, gap) {
        (true, _) if p < -sigma_c => Flip::Detach,
        (false, Some(g)) if g < 0.0 => Flip::Attach,
        _ => Flip::Keep,
    }
}

/// The fraction t ∈ [0, 1] of a load step at which an element of C with pressure moving
/// linearly from `p_old` to `p_new` (stresses) reaches −σ_c; 1 if it does not within the
/// step.
pub fn crossing_fraction(p_old: f64, p_new: f64, sigma_c: f64) -> f64 {
    if p_new < -sigma_c && p_new < p_old {
        ((-sigma_c - p_old) / (p_new - p_old)).clamp(0.0, 1.0)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sweep_detaches_beyond_the_stress_and_attaches_on_overlap() {
        assert_eq!(sweep_element(true, -2.0, None, 1.0), Flip::Detach);
        assert_eq!(sweep_element(true, -1.0, Some(-1.0), 1.0), Flip::Keep);
        assert_eq!(sweep_element(false, 0.0, Some(-1e-12), 1.0), Flip::Attach);
        assert_eq!(sweep_element(false, 0.0, None, 1.0), Flip::Keep);
        assert_eq!(sweep_element(false, 0.0, Some(0.0), 1.0), Flip::Keep);
        // Non-adhesive: any tension detaches.
        assert_eq!(sweep_element(true, -1e-12, None, 0.0), Flip::Detach);
    }

    #[test]
    fn the_crossing_is_where_the_line_meets_the_stress() {
        assert_eq!(crossing_fraction(0.0, -2.0, 1.0), 0.5);
        assert_eq!(crossing_fraction(0.0, -0.5, 1.0), 1.0);
        assert_eq!(crossing_fraction(-1.5, -2.0, 1.0), 0.0);
        assert_eq!(crossing_fraction(-3.0, -2.0, 1.0), 1.0);
    }
}
