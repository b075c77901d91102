//! What a standard asks of an area, as the scene resolves it: the parts of an area a grid
//! measures ([`AreaPart`]), the quantities judged ([`Quantity`]), one limit
//! ([`Requirement`]) and the standards ([`Standard`]): EN 12464-1's `[[area]]`s
//! ([`super::area`]) and EN 1838's `[[emergency]]` areas ([`super::emergency`]) are both
//! judged by these; `calc::requirements` judges them.

use serde::Serialize;

/// The part of an area a grid measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AreaPart {
    /// The task area (or the area itself).
    Task,
    /// The immediate surrounding.
    Surrounding,
    /// The background.
    Background,
    /// The cylindrical illuminance over the task area.
    Cylindrical,
    /// A room's wall: the side of its outline from corner k to corner k + 1 (from 0).
    Wall(usize),
    /// A room's ceiling.
    Ceiling,
    /// An escape route's centre line (EN 1838).
    CentreLine,
    /// An escape route's central band (EN 1838).
    CentralBand,
    /// An emergency luminaire (by index into the scene's luminaires), for its glare.
    Luminaire(usize),
}

impl Serialize for AreaPart {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl AreaPart {
    /// The part's name, as `calc.json` writes it (each wall's grid names the wall).
    pub fn name(self) -> &'static str {
        match self {
            AreaPart::Task => "task",
            AreaPart::Surrounding => "surrounding",
            AreaPart::Background => "background",
            AreaPart::Cylindrical => "cylindrical",
            AreaPart::Wall(_) => "wall",
            AreaPart::Ceiling => "ceiling",
            AreaPart::CentreLine => "centre line",
            AreaPart::CentralBand => "central band",
            AreaPart::Luminaire(_) => "luminaire",
        }
    }

    /// The part as a reader names it: its name, with the wall's number.
    pub fn label(self) -> String {
        match self {
            AreaPart::Wall(k) => format!("wall {}", k + 1),
            other => other.name().to_string(),
        }
    }

    /// The suffix of the part's grid name (after the area's name): walls are numbered
    /// from 1.
    pub fn suffix(self) -> String {
        match self {
            AreaPart::Task => String::new(),
            AreaPart::Surrounding => " surrounding".into(),
            AreaPart::Background => " background".into(),
            AreaPart::Cylindrical => " Ez".into(),
            AreaPart::Wall(k) => format!(" wall {}", k + 1),
            AreaPart::Ceiling => " ceiling".into(),
            AreaPart::CentreLine => " centre line".into(),
            AreaPart::CentralBand => " central band".into(),
            AreaPart::Luminaire(k) => format!(" L{}", k + 1),
        }
    }
}

/// A quantity a requirement is set on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Maintained mean illuminance, lx.
    Em,
    /// Uniformity Emin/Em.
    U0,
    /// Maintained mean cylindrical illuminance, lx.
    Ez,
    /// The highest UGR at the observers.
    Ugr,
    /// The lowest colour rendering index of the luminaires.
    Ra,
    /// Minimum illuminance, lx.
    Emin,
    /// Emax/Emin (at most: EN 1838's 40:1).
    MaxToMin,
    /// Emin/Emax.
    G2,
    /// The highest intensity 60–90° from the downward vertical, cd (at most).
    GlareIntensity,
}

impl Serialize for Quantity {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl Quantity {
    /// The quantity's name, as `calc.json` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Em => "Em",
            Quantity::U0 => "U0",
            Quantity::Ez => "Ez",
            Quantity::Ugr => "UGR",
            Quantity::Ra => "Ra",
            Quantity::Emin => "Emin",
            Quantity::MaxToMin => "Emax/Emin",
            Quantity::G2 => "g2",
            Quantity::GlareIntensity => "I 60-90°",
        }
    }

    /// Whether the achieved value must be at most the limit (UGR) rather than at least.
    pub fn is_upper_limit(self) -> bool {
        matches!(
            self,
            Quantity::Ugr | Quantity::MaxToMin | Quantity::GlareIntensity
        )
    }
}

/// One requirement of an area.
#[derive(Debug, Clone, PartialEq)]
pub struct Requirement {
    /// The part it is judged on.
    pub part: AreaPart,
    /// The quantity.
    pub quantity: Quantity,
    /// The limit.
    pub required: f64,
    /// Where the limit comes from: `None` when the scene gives it, else the standard's
    /// rule that made it.
    pub derived: Option<&'static str>,
}

/// The standard an area is judged by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Standard {
    /// EN 12464-1:2021, lighting of indoor work places.
    En12464,
    /// EN 1838:2013, emergency lighting.
    En1838,
}

impl Standard {
    /// The standard as a reviewer names it.
    pub fn name(self) -> &'static str {
        match self {
            Standard::En12464 => "EN 12464-1:2021",
            Standard::En1838 => "EN 1838:2013",
        }
    }
}
