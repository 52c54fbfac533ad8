"""Mechanism-independent leg-wise (divide and conquer) kinematic calibration: legs and mechanisms
(:mod:`.mechanism`), identification — Levenberg–Marquardt or Gauss–Newton — and identifiability
(:mod:`.identify`), observability indices and pose selection (:mod:`.selection`), the study, its
budgets and pose sets (:mod:`.study`), the seeded Monte Carlo and its sweeps (:mod:`.montecarlo`),
paired statistics with failed trials left out (:mod:`.statistics`) and the cost of the normal
equations (:mod:`.cost`)."""
