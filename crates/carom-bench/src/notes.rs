//! What a peer engine could not express of a carom world, said instead of dropped silently.

use std::collections::BTreeMap;

/// Things of a carom world a peer's copy leaves out or approximates, each with how often it
/// came up (a scene of 500 mouse joints gives one line, not 500).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Notes {
    counts: BTreeMap<String, usize>,
}

impl Notes {
    /// Records one more instance of `what`.
    pub fn add(&mut self, what: impl Into<String>) {
        *self.counts.entry(what.into()).or_default() += 1;
    }

    /// Nothing was left out or approximated.
    pub fn is_empty(&self) -> bool {
        self.counts.is_empty()
    }

    /// One line per kind of thing, with its count when it came up more than once, in a
    /// stable order.
    pub fn lines(&self) -> Vec<String> {
        self.counts
            .iter()
            .map(|(what, &n)| match n {
                1 => what.clone(),
                n => format!("{what} (× {n})"),
            })
            .collect()
    }

    /// Whether any line contains `text`.
    pub fn mentions(&self, text: &str) -> bool {
        self.counts.keys().any(|k| k.contains(text))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_are_counted_once_each() {
        let mut notes = Notes::default();
        assert!(notes.is_empty());
        notes.add("a mouse joint: not translated");
        notes.add("a mouse joint: not translated");
        notes.add("a motor joint: not translated");
        assert_eq!(
            notes.lines(),
            [
                "a motor joint: not translated",
                "a mouse joint: not translated (× 2)"
            ]
        );
        assert!(notes.mentions("mouse"));
    }
}
