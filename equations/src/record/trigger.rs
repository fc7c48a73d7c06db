//! The kind of a mode decision's trigger, spelled as the events table writes it.

use crate::hybrid::Trigger;

/// The quantity whose crossing caused a mode decision ([`Trigger`] without its numbers).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TriggerKind {
    /// At the start, rolling would need more friction than `μ_st N`.
    InitialFriction,
    /// While rolling, `T/N` reached `μ_st`.
    FrictionLimit,
    /// While sliding, the slip speed reached zero.
    SlipStopped,
}

impl TriggerKind {
    /// Every kind, in the order above.
    pub const ALL: [TriggerKind; 3] = [
        TriggerKind::InitialFriction,
        TriggerKind::FrictionLimit,
        TriggerKind::SlipStopped,
    ];

    /// The kind's name in written files (its serde name).
    pub fn name(self) -> &'static str {
        match self {
            TriggerKind::InitialFriction => "initial_friction",
            TriggerKind::FrictionLimit => "friction_limit",
            TriggerKind::SlipStopped => "slip_stopped",
        }
    }

    /// What [`Trigger::value`] holds for this kind.
    pub fn value_meaning(self) -> &'static str {
        match self {
            TriggerKind::InitialFriction | TriggerKind::FrictionLimit => "T/N",
            TriggerKind::SlipStopped => "T_r/N_r rolling would need",
        }
    }
}

impl Trigger {
    /// The trigger's kind.
    pub fn kind(&self) -> TriggerKind {
        match self {
            Trigger::InitialFriction { .. } => TriggerKind::InitialFriction,
            Trigger::FrictionLimit { .. } => TriggerKind::FrictionLimit,
            Trigger::SlipStopped { .. } => TriggerKind::SlipStopped,
        }
    }

    /// The friction ratio that decided ([`TriggerKind::value_meaning`]).
    pub fn value(&self) -> f64 {
        match *self {
            Trigger::InitialFriction { ratio } | Trigger::FrictionLimit { ratio } => ratio,
            Trigger::SlipStopped { rolling_ratio, .. } => rolling_ratio,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_the_serde_names() {
        use serde::de::value::{Error, StrDeserializer};
        use serde::de::IntoDeserializer;
        for kind in TriggerKind::ALL {
            let de: StrDeserializer<'_, Error> = kind.name().into_deserializer();
            let back: TriggerKind = serde::Deserialize::deserialize(de).unwrap();
            assert_eq!(back, kind);
        }
    }

    #[test]
    fn value_is_the_ratio_that_decided() {
        let t = Trigger::SlipStopped {
            rolling_ratio: 0.3,
            rolling_normal: 4.0,
        };
        assert_eq!((t.kind(), t.value()), (TriggerKind::SlipStopped, 0.3));
        let t = Trigger::FrictionLimit { ratio: 0.2 };
        assert_eq!((t.kind(), t.value()), (TriggerKind::FrictionLimit, 0.2));
    }
}
