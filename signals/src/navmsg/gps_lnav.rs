//! GPS LNAV navigation message.
