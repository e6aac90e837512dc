//! Which states' fields a run keeps ([`FieldChoice`]), in the words both front ends write:
//! "none", "minimum", "every:K" or "states:I,J,…". What they cost in memory is the
//! analysis's.

/// Which states' fields a run keeps.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum FieldChoice {
    /// None (the default: a long run holds no field).
    #[default]
    None,
    /// The state of minimum force (the adhesive force's state).
    Minimum,
    /// Every k-th recorded state (0, k, 2k, …), and the force minimum.
    Every(usize),
    /// The recorded states of these indices (0 is the first press), and the force minimum.
    States(Vec<usize>),
}

impl FieldChoice {
    /// Parse "none", "minimum", "every:K" or "states:I,J,…" (the CLI's and Python's words).
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "{text:?} is not a choice of fields: \"none\", \"minimum\", \"every:K\" (every K-th \
                 state, K ≥ 1) or \"states:I,J\" (those states, counted from 0)"
            )
        };
        match text.trim() {
            "none" => Ok(FieldChoice::None),
            "minimum" => Ok(FieldChoice::Minimum),
            t => {
                if let Some(k) = t.strip_prefix("every:") {
                    match k.trim().parse::<usize>() {
                        Ok(k) if k >= 1 => Ok(FieldChoice::Every(k)),
                        _ => Err(bad()),
                    }
                } else if let Some(list) = t.strip_prefix("states:") {
                    let picked: Result<Vec<usize>, _> =
                        list.split(',').map(|s| s.trim().parse::<usize>()).collect();
                    match picked {
                        Ok(v) if !v.is_empty() => Ok(FieldChoice::States(v)),
                        _ => Err(bad()),
                    }
                } else {
                    Err(bad())
                }
            }
        }
    }

    /// The choice as [`FieldChoice::parse`] reads it.
    pub fn name(&self) -> String {
        match self {
            FieldChoice::None => "none".into(),
            FieldChoice::Minimum => "minimum".into(),
            FieldChoice::Every(k) => format!("every:{k}"),
            FieldChoice::States(v) => format!(
                "states:{}",
                v.iter()
                    .map(|i| i.to_string())
                    .collect::<Vec<_>>()
                    .join(",")
            ),
        }
    }

    /// Whether no field is kept.
    pub fn is_none(&self) -> bool {
        *self == FieldChoice::None
    }

    /// How many states' fields a run that records about `states` states keeps (the force
    /// minimum's among them).
    pub fn kept_states(&self, states: usize) -> usize {
        match self {
            FieldChoice::None => 0,
            FieldChoice::Minimum => 1,
            FieldChoice::Every(k) => states / (*k).max(1) + 2,
            FieldChoice::States(v) => v.len() + 1,
        }
    }
}
