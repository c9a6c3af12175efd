//! The fast synchronisation scheme of thesis section 3.3 (figure 3.3-6): a fine Doppler
//! estimate from the PMF-FFT acquisition hands over to a carrier tracking loop in which an
//! unscented Kalman filter replaces the phase discriminator and the loop filter.

pub mod ukf;
