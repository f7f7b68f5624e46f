pub mod mechanisms;
