#pragma once
// The impairment options every client binary takes (--loss, --latency-ms, --jitter-ms,
// --duplicate, --reorder: docs/RELIABILITY.md), declared once. Header-only: only executables
// include it (they link CLI11).
#include "transport/impairment.hpp"

#include <CLI/CLI.hpp>

namespace foresight::protocol {

inline void add_impairment_options(CLI::App& app, ImpairmentConfig& c) {
  app.add_option("--loss", c.loss, "Impairment: share of datagrams lost, each way")->check(CLI::Range(0.0, 1.0));
  app.add_option("--latency-ms", c.latency_ms, "Impairment: one-way delay")->check(CLI::Range(0.0, 10000.0));
  app.add_option("--jitter-ms", c.jitter_ms, "Impairment: delay varies by up to this")->check(CLI::Range(0.0, 10000.0));
  app.add_option("--duplicate", c.duplicate, "Impairment: share of datagrams duplicated")->check(CLI::Range(0.0, 1.0));
  app.add_option("--reorder", c.reorder, "Impairment: share of datagrams held back behind later ones")
      ->check(CLI::Range(0.0, 1.0));
}

}  // namespace foresight::protocol
