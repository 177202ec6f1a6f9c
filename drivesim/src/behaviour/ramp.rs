//! The ramps a description gives its setpoints (`[[ramp]]`): how fast the simulated motor's
//! speed moves towards a setpoint, from the parameters the ramp names, in the form the manual
//! gives them — a time from 0 to a full scale (Lafert speed ramp up / down in ms, switched by
//! the ramp enable), a rate (CiA 402 profile acceleration / deceleration, units per second) or a
//! delta speed over a delta time (CiA 402 vl 6048h / 6049h) — and whether a polarity bit
//! reverses the setpoint (Lafert speed polarity 0x0043).

use drivegen::ir::{per_second, Ramp, Scale, Slope};

use crate::store::{ParamId, Store};

/// Span a ramp time refers to while its full-scale parameter reads 0 (not set: a Lafert full
/// scale depends on the motor fitted).
const DEFAULT_FULL_SCALE: f64 = 3000.0;

/// A time parameter and how many of its raw units make a second.
#[derive(Debug, Clone, Copy)]
struct Time {
    id: ParamId,
    per_second: f64,
}

impl Time {
    /// The parameter `name` as a time: its unit (`ms`, `s`) and its fixed scale (Lenze smd C12:
    /// 0.1 s per raw unit, 10 raw units a second); a time scaled at run time is not one.
    fn find(store: &Store, name: &str) -> Option<Self> {
        let id = store.id(name)?;
        let parameter = store.parameter(id);
        let factor = match &parameter.scale {
            None => 1.0,
            Some(Scale::Fixed(scale)) => scale.factor.to_f64(),
            Some(Scale::Runtime { .. }) => return None,
        };
        let per_second = per_second(parameter.unit.as_deref()?)? / factor;
        per_second.is_finite().then_some(Self { id, per_second })
    }
}

/// One direction of a ramp, by parameter.
#[derive(Debug, Clone, Copy)]
enum SlopeIds {
    /// From 0 to the full scale in this time.
    Time(Time),
    /// Speed units per second, times this many (1000 for a rate per millisecond).
    Rate(ParamId, f64),
    /// `speed` units in `time`.
    Delta { speed: ParamId, time: Time },
}

impl SlopeIds {
    fn find(store: &Store, slope: &Slope) -> Option<Self> {
        Some(match slope {
            Slope::Time { time } => SlopeIds::Time(Time::find(store, time)?),
            Slope::Rate { rate, per } => SlopeIds::Rate(
                store.id(rate)?,
                per.as_deref().map_or(Some(1.0), per_second)?,
            ),
            Slope::Delta { speed, time } => SlopeIds::Delta {
                speed: store.id(speed)?,
                time: Time::find(store, time)?,
            },
        })
    }
}

/// A setpoint's ramp, its parameters looked up once.
#[derive(Debug, Clone, Copy)]
pub struct SetpointRamp {
    setpoint: ParamId,
    up: SlopeIds,
    down: SlopeIds,
    full_scale: Option<ParamId>,
    enable: Option<ParamId>,
    /// The polarity parameter and bit: set, the motor runs at -setpoint.
    polarity: Option<(ParamId, u32)>,
}

impl SetpointRamp {
    /// Every ramp of the description whose parameters the store holds.
    pub fn detect(store: &Store) -> Vec<Self> {
        let ramps = &store.device().ramps;
        ramps.iter().filter_map(|r| Self::find(store, r)).collect()
    }

    fn find(store: &Store, ramp: &Ramp) -> Option<Self> {
        let optional = |name: &Option<String>| name.as_deref().and_then(|n| store.id(n));
        Some(Self {
            setpoint: store.id(&ramp.setpoint)?,
            up: SlopeIds::find(store, &ramp.up)?,
            down: SlopeIds::find(store, &ramp.down)?,
            full_scale: optional(&ramp.full_scale),
            enable: optional(&ramp.enable),
            polarity: ramp
                .polarity
                .as_ref()
                .and_then(|p| Some((store.id(&p.parameter)?, p.bit))),
        })
    }

    /// Whether this is the ramp of `setpoint`.
    pub fn shapes(&self, setpoint: ParamId) -> bool {
        self.setpoint == setpoint
    }

    /// -1 while the polarity bit is set (the demand is multiplied by -1), else 1.
    pub fn sign(&self, store: &Store) -> f64 {
        match self.polarity {
            Some((id, bit)) if (store.int(id).unwrap_or(0) >> bit) & 1 == 1 => -1.0,
            _ => 1.0,
        }
    }

    /// Speed units per second at the deceleration held in `rate` (the quick stop deceleration),
    /// counted per the same time as this ramp's own deceleration rate (Kinco: per millisecond);
    /// `None` when it reads 0 (the speed jumps).
    pub fn rate_of(&self, store: &Store, rate: ParamId) -> Option<f64> {
        let per_second = match self.down {
            SlopeIds::Rate(_, per_second) => per_second,
            SlopeIds::Time(_) | SlopeIds::Delta { .. } => 1.0,
        };
        Some(store.int(rate).unwrap_or(0) as f64 * per_second).filter(|r| *r > 0.0)
    }

    /// Speed units per second towards a setpoint further from zero (`speeding_up`) or nearer to
    /// it; `None` when the ramp is off or its time or rate is zero (the speed jumps).
    pub fn rate(&self, store: &Store, speeding_up: bool) -> Option<f64> {
        let value = |id| store.int(id).unwrap_or(0) as f64;
        if self.enable.is_some_and(|id| value(id) == 0.0) {
            return None;
        }
        let slope = if speeding_up { self.up } else { self.down };
        let rate = match slope {
            SlopeIds::Time(time) => {
                let span = self
                    .full_scale
                    .map(value)
                    .filter(|v| *v > 0.0)
                    .unwrap_or(DEFAULT_FULL_SCALE);
                let t = value(time.id);
                (t > 0.0).then(|| span * time.per_second / t)?
            }
            SlopeIds::Rate(rate, per_second) => value(rate) * per_second,
            SlopeIds::Delta { speed, time } => {
                let t = value(time.id);
                (t > 0.0).then(|| value(speed) * time.per_second / t)?
            }
        };
        Some(rate).filter(|r| *r > 0.0)
    }
}
