//! Effects a world simulates. What a scene does not name is not computed at all.

/// One optional part of the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[non_exhaustive]
pub enum Effect {
    /// Gravity accelerates dynamic bodies.
    Gravity,
    /// Bodies' drag coefficients slow them down.
    Drag,
    /// Coulomb friction at contacts (no tangent impulse is computed without it).
    Friction,
    /// Bounces (no restitution pass without it).
    Restitution,
    /// Impacts at any speed: fast bodies are swept against static ones (bullets against every
    /// body) so they cannot tunnel, and, with [`crate::WorldSettings::look_ahead`] (the
    /// default), contacts between faces are made a step ahead (as far as the pair can close in
    /// a step) so the solver stops the approach at the surface.
    Continuous,
    /// Islands of resting bodies sleep.
    Sleeping,
}

impl Effect {
    /// Every effect.
    pub const ALL: [Effect; 6] = [
        Effect::Gravity,
        Effect::Drag,
        Effect::Friction,
        Effect::Restitution,
        Effect::Continuous,
        Effect::Sleeping,
    ];

    /// The effect's name, as scene files and the command line spell it.
    pub fn name(self) -> &'static str {
        match self {
            Effect::Gravity => "gravity",
            Effect::Drag => "drag",
            Effect::Friction => "friction",
            Effect::Restitution => "restitution",
            Effect::Continuous => "continuous",
            Effect::Sleeping => "sleeping",
        }
    }

    /// The effect with this name, if there is one.
    pub fn from_name(name: &str) -> Option<Effect> {
        Effect::ALL.into_iter().find(|e| e.name() == name)
    }

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A set of [`Effect`]s.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Effects(u8);

impl Default for Effects {
    /// Everything on, as a general-purpose engine runs.
    fn default() -> Self {
        Effects::ALL
    }
}

impl Effects {
    /// No effects: bodies move by their velocities and collide, nothing else.
    pub const NONE: Effects = Effects(0);

    /// Every effect.
    pub const ALL: Effects = Effects(0b11_1111);

    /// The set holding exactly these effects.
    pub fn of(effects: &[Effect]) -> Self {
        effects.iter().fold(Effects::NONE, |set, e| set.with(*e))
    }

    /// True when the set holds `effect`.
    #[inline]
    pub fn contains(self, effect: Effect) -> bool {
        self.0 & effect.bit() != 0
    }

    /// The set with `effect` added.
    #[inline]
    pub fn with(self, effect: Effect) -> Self {
        Effects(self.0 | effect.bit())
    }

    /// The set with `effect` removed.
    #[inline]
    pub fn without(self, effect: Effect) -> Self {
        Effects(self.0 & !effect.bit())
    }

    /// The set with `effect` switched on or off.
    #[inline]
    pub fn switched(self, effect: Effect, on: bool) -> Self {
        if on {
            self.with(effect)
        } else {
            self.without(effect)
        }
    }

    /// Switches `effect` on or off in place.
    pub fn set(&mut self, effect: Effect, on: bool) {
        *self = self.switched(effect, on);
    }

    /// The effects in the set, in [`Effect::ALL`] order.
    pub fn iter(self) -> impl Iterator<Item = Effect> {
        Effect::ALL.into_iter().filter(move |e| self.contains(*e))
    }
}

/// Effects are written as the list of those on, by name.
#[cfg(feature = "serde")]
mod written {
    use super::{Effect, Effects};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    impl Serialize for Effects {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            let on: Vec<Effect> = Effect::ALL
                .into_iter()
                .filter(|&e| self.contains(e))
                .collect();
            on.serialize(serializer)
        }
    }

    impl<'de> Deserialize<'de> for Effects {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            let list = Vec::<Effect>::deserialize(deserializer)?;
            Ok(list.into_iter().fold(Effects::NONE, Effects::with))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_add_remove_and_name() {
        let set = Effects::of(&[Effect::Gravity, Effect::Sleeping]);
        assert!(set.contains(Effect::Gravity) && set.contains(Effect::Sleeping));
        assert!(!set.contains(Effect::Friction));
        assert_eq!(
            set.iter().collect::<Vec<_>>(),
            vec![Effect::Gravity, Effect::Sleeping]
        );
        let mut set = set.without(Effect::Gravity).with(Effect::Drag);
        set.set(Effect::Sleeping, false);
        assert_eq!(set, Effects::of(&[Effect::Drag]));
        assert_eq!(Effects::ALL.iter().count(), 6);
        for e in Effect::ALL {
            assert_eq!(Effect::from_name(e.name()), Some(e));
        }
        assert_eq!(Effect::from_name("magnetism"), None);
    }
}
