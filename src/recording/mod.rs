//! Recording: frames into a Rerun recording stream, and where that stream goes.
//!
//! * [`logger`]: [`RopeLogger`](logger::RopeLogger), the [`FrameSink`](crate::run::FrameSink)
//!   that draws frames as Rerun entities (it knows nothing of the equations); what it keeps
//!   per method ([`lane_log`]), how each shape is drawn ([`shapes`]) and what is logged once
//!   ([`styling`]);
//! * [`entities`]: the entity paths, timelines and time series, by name;
//! * [`budget`]: how long a page can stay open on a history, worked out before the run;
//! * [`live`]: what viewers of a run that never ends are sent: a live picture and a history;
//! * [`blueprint`]: the viewer's layout, one function per view; [`colour`]: the tension map;
//! * [`destinations`]: the flags that name where the recording goes, and opening them;
//! * [`viewer_sinks`]: links to viewers that can never stall a run; [`memory`]: a destination
//!   in memory, for a caller in the same process;
//! * [`error`]: what can go wrong here.

pub mod blueprint;
pub mod budget;
pub mod colour;
pub mod destinations;
pub mod entities;
pub mod error;
pub mod lane_log;
pub mod live;
pub mod logger;
pub mod memory;
pub mod shapes;
pub mod styling;
pub mod sweep_view;
pub mod table;
pub mod viewer_sinks;
