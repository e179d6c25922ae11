//! The surface shaders of the paper's Table 1, one module each.

pub mod brick;
pub mod checker;
pub mod glass;
pub mod granite;
pub mod parquet;
pub mod plastic;
pub mod screen;
pub mod starball;
pub mod venus;
pub mod wood;

pub use brick::Brick;
pub use checker::Checker;
pub use glass::Glass;
pub use granite::Granite;
pub use parquet::Parquet;
pub use plastic::Plastic;
pub use screen::Screen;
pub use starball::Starball;
pub use venus::Venus;
pub use wood::Wood;
