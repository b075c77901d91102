//! Weather data: hourly records of the sun and sky at a site, read from EnergyPlus weather
//! files ([`epw`]), for the planning tests that count hours of sunshine
//! ([`crate::planning`]) and, later, climate-based daylight.

pub mod epw;

pub use epw::{read_epw, Weather, WeatherError, WeatherHour, WeatherLocation};
