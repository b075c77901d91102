//! Diffuse transmission (Wallner §4.2): a translucent surface (an opal diffuser, a
//! luminous ceiling, a curtain) sends the share τ of the light arriving on one side out of
//! its other side, diffusely.
//!
//! Each of its triangles gets a back face for radiosity: the same corners in the other
//! winding, so the back is a surface of its own with its own elements and shooters and
//! emits into the other hemisphere. An element of a translucent material receives from
//! both sides of its plane: what arrives on its front it reflects with ρ, what arrives on
//! its back (on its twin's front) it transmits with τ. The front's exitance is then
//! ρ E_front + τ E_back and the back's ρ E_back + τ E_front, with no coupling between the
//! twins beyond sharing a place: visibility maps hold distances, and the two faces lie at
//! the same one. The back faces come after the scene's own triangles, so the light map of
//! triangle `t` of the scene stays triangle `t`'s.

pub use crate::scene::back_faces::{is_translucent, with_back_faces};
