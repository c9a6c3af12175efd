//! BeiDou D1 (MEO/IGSO) and D2 (GEO) navigation messages.
