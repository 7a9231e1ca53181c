//! Tables of subdivision (OpenSubdiv's `far` layer): the stencils of every
//! new vertex recorded once for a topology ([`StencilPlan`], CSR rows per
//! level in [`rows`], packed by distinct weights in [`packed`]) and
//! re-applied to new control values: positions each animation frame,
//! colours and texture coordinates ([`attributes`]).

pub(crate) mod attributes;
pub(crate) mod face_varying;
pub(crate) mod packed;
pub(crate) mod plan;
pub(crate) mod poly_plan;
pub(crate) mod rows;

pub use plan::{PlanScratch, StencilPlan};
pub use rows::{LevelPlan, Point};
