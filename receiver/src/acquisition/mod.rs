//! Acquisition: parallel code-phase search (PCPS) and the PMF-FFT of thesis section 3.3.1.
