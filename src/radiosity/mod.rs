//! Progressive radiosity (Wallner ch. 2 and 4; Cohen et al. 1988; Coombe et al. 2004):
//! light-map elements, form factors, and the CPU reference solver.

pub mod elements;
pub mod form_factor;
