//! The engines a sweep can run: carom, and Box2D v3 and Rapier rebuilt from the same carom
//! world ([`super::peer`]).

/// A physics engine a sweep point runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Engine {
    /// carom itself.
    Carom,
    /// Box2D v3 (3.2.0 through `boxdd`).
    Box2d,
    /// Rapier 0.36.
    Rapier,
}

impl Engine {
    /// Every engine, carom first.
    pub const ALL: [Engine; 3] = [Engine::Carom, Engine::Box2d, Engine::Rapier];

    /// The engine's name in reports, charts and the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Carom => "carom",
            Engine::Box2d => "Box2D",
            Engine::Rapier => "Rapier",
        }
    }

    /// The engine's colour in charts and in the app's plot, sRGB.
    pub fn color(self) -> [u8; 3] {
        match self {
            Engine::Carom => [200, 30, 30],
            Engine::Box2d => [30, 150, 60],
            Engine::Rapier => [40, 90, 220],
        }
    }

    /// The engine named `name` (case ignored; `box2d` and `rapier` as the command line
    /// spells them).
    pub fn from_name(name: &str) -> Option<Engine> {
        Engine::ALL
            .into_iter()
            .find(|e| e.name().eq_ignore_ascii_case(name.trim()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engines_are_found_by_the_names_the_command_line_uses() {
        assert_eq!(Engine::from_name("box2d"), Some(Engine::Box2d));
        assert_eq!(Engine::from_name(" Rapier"), Some(Engine::Rapier));
        assert_eq!(Engine::from_name("carom"), Some(Engine::Carom));
        assert_eq!(Engine::from_name("bullet"), None);
    }
}
