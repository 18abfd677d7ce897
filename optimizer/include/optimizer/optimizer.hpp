// lodopt optimizer: everything in one include. The module depends on the C++ standard library
// only; docs/optimizer.md describes the algorithms, their parameters and measured behaviour.
#pragma once

#include "optimizer/algorithm.hpp"
#include "optimizer/baselines.hpp"
#include "optimizer/checked_evaluator.hpp"
#include "optimizer/engine_rules.hpp"
#include "optimizer/gapso.hpp"
#include "optimizer/heuristics.hpp"
#include "optimizer/mckp.hpp"
#include "optimizer/problem.hpp"
#include "optimizer/random.hpp"
#include "optimizer/repair.hpp"
#include "optimizer/search.hpp"
#include "optimizer/synthetic.hpp"
