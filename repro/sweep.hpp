/// @file sweep.hpp
/// @brief A sweep: a grid of runs of the paper's benchmark, each one result line, run in this process
/// (run_configurations, on the threads) or written out as a job list, one self-contained command per line,
/// each writing one result file, for GNU parallel (locally or across hosts, --sshloginfile) or a SLURM
/// array; merge_results joins the files into the same bytes as the in-process sweep
/// (experiments/sweep.cpp, the ctest entry sweep_job_list).
/// The job grid (sweep/job_grid.hpp) and the batched scheduler (sweep/batched.hpp), included together.
#pragma once

#include "sweep/batched.hpp"
#include "sweep/job_grid.hpp"
