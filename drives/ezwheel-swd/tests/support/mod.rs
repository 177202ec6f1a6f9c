pub mod simulated_swd;
