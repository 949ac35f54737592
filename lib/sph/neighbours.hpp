#pragma once
/// \file
/// \brief Smoothing lengths and the neighbour list, built once per step and shared by every pass.
///
/// One include for the whole neighbour search; the pieces, each readable on its own:
///  - neighbour_list.hpp: the list every pass reads (Neighbour, NeighbourList), the positions
///    one array per axis its SIMD loops read (PositionView, PositionArrays), and the check that
///    masses are positive;
///  - smoothing_length.hpp: the physics of h -- the three rules (SmoothingLengthRule: fixed,
///    neighbour number with the lattice-shell handling, h from density by Newton iteration)
///    and how each settles h from a particle's candidates;
///  - neighbour_search.hpp: NeighbourSearch, which searches the cell grid, applies the rule and
///    writes the list (the pairs kept on each side, the one-sided pairs handed over);
///  - candidate_reuse.hpp: the members of NeighbourSearch that keep a particle's candidates from
///    step to step while its neighbourhood has moved little;
///  - search_blocks.hpp: the blocks of particles in which the search keeps its candidates and
///    pairs;
///  - keep_closer.hpp: the compaction that keeps the candidates within 2h (AVX-512 where
///    available, a plain loop elsewhere).

#include "sph/neighbours/candidate_reuse.hpp"
#include "sph/neighbours/keep_closer.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/neighbours/neighbour_search.hpp"
#include "sph/neighbours/search_blocks.hpp"
#include "sph/neighbours/smoothing_length.hpp"
