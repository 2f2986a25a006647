// rbla_stiff_bench: runs every stiff and extreme case (tests/stiff/stiff_cases.hpp, the slow
// ones too) through the model stage and the analysis exactly as `rbla solve` does, compares
// with each case's closed-form reference, and writes the markdown table docs/stability.md.
//
//   rbla_stiff_bench [--markdown FILE] [--filter TEXT] [--fast] [--dump DIR]
//
//   --markdown FILE  write the table there (default: print it to standard output)
//   --filter TEXT    only the cases whose name contains TEXT
//   --fast           skip the slow cases (those only the benchmark runs)
//   --dump DIR       also write each case's model JSON to DIR/<name>.json (for `rbla solve`)
//
// Exit code 0 when every case met its expectation, 1 otherwise (the table says which).
#include "stiff_cases.hpp"
#include "stiff_checks.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using rbla::stiff::Expect;
using rbla::stiff::StiffCase;

/// First line of a command's output ("" when it fails).
std::string first_line_of(const std::string& command) {
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[512];
    if (fgets(buffer, sizeof buffer, pipe)) out = buffer;
    pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string machine() {
  std::string cpu;
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  const std::string cores = first_line_of("nproc 2>/dev/null");
  const std::string os = first_line_of("uname -sr 2>/dev/null");
  return cpu + ", " + cores + " cores, " + os;
}

std::string fmt(double v, int digits = 6) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream o;
  o << std::setprecision(digits) << v;
  return o.str();
}

std::string escape(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else out += c;
  }
  return out;
}

struct Row {
  const StiffCase* c = nullptr;
  std::string verdict;
  double value = std::nan("");
  double error = std::nan("");
  int ipm_iterations = 0;
  int solves = 0;
  double seconds = 0.0;
  bool ok = false;
  std::string note;
};

Row run_case(const StiffCase& c) {
  Row row;
  row.c = &c;
  const auto start = std::chrono::steady_clock::now();
  try {
    const rbla::stiff::StiffRun run = rbla::stiff::run_model(c.model);
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& r = run.result;
    row.verdict = rbla::analysis::to_string(r.verdict);
    row.value = rbla::stiff::value_of(r);
    row.solves = r.non_associative.empty() ? 1 : static_cast<int>(r.non_associative.size());
    if (r.non_associative.empty()) {
      row.ipm_iterations = r.solver_info.iterations;
    } else {
      for (const auto& step : r.non_associative) row.ipm_iterations += step.interior_point_iterations;
    }
    row.ok = row.verdict == rbla::stiff::to_string(c.expect);
    if (c.expect == Expect::Collapse && row.ok) {
      row.error = std::abs(row.value - c.reference) / std::abs(c.reference);
      row.ok = std::abs(row.value - c.reference) <= c.rel_tol * std::abs(c.reference) + c.abs_tol;
    }
    const auto bad = rbla::stiff::non_finite_fields(r);
    if (!bad.empty()) {
      row.ok = false;
      row.note = std::to_string(bad.size()) + " non-finite values (" + bad.front() + ")";
    }
    if (r.friction_model == rbla::model::FrictionModel::NonAssociative && r.verdict == rbla::analysis::Verdict::Collapse &&
        !r.non_associative_converged) {
      // As rbla_stiff_tests: the scheme must converge where its tolerance is reachable, i.e. where
      // tolerance x |alpha| >= 1e-7 (the solves are accurate to ~1e-8 absolute on a multiplier).
      const double na_tol = c.model["analysis"]["non_associative"].value("tolerance", 1e-4);
      const bool reachable = r.base_reaction.has_value() || na_tol * std::abs(row.value) >= 1e-7;
      if (reachable) row.ok = false;
      row.note += std::string(row.note.empty() ? "" : "; ") + "non-associative scheme not converged" +
                  (reachable ? "" : " (tolerance below the solver's accuracy at this alpha: not required)");
    }
  } catch (const std::exception& e) {
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    row.verdict = "exception";
    row.note = e.what();
  }
  return row;
}

/// A twin pair: the twin's alpha is the reference.
Row run_twin(const rbla::stiff::TwinCase& t, StiffCase& holder) {
  const rbla::stiff::StiffRun twin = rbla::stiff::run_model(t.twin);
  holder.name = t.name;
  holder.varies = t.varies;
  holder.expect = Expect::Collapse;
  holder.reference = rbla::stiff::value_of(twin.result);
  holder.source = t.source + " (its alpha, " + rbla::analysis::to_string(twin.result.verdict) + ")";
  holder.rel_tol = t.rel_tol;
  holder.abs_tol = 0.0;
  holder.slow = t.slow;
  holder.model = t.model;
  return run_case(holder);
}

}  // namespace

int main(int argc, char** argv) {
  std::string markdown, filter, dump;
  bool fast = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--markdown" && i + 1 < argc) markdown = argv[++i];
    else if (arg == "--filter" && i + 1 < argc) filter = argv[++i];
    else if (arg == "--dump" && i + 1 < argc) dump = argv[++i];
    else if (arg == "--fast") fast = true;
    else {
      std::cerr << "usage: rbla_stiff_bench [--markdown FILE] [--filter TEXT] [--fast] [--dump DIR]\n";
      return 2;
    }
  }
  std::string command = "build-stiff-bench/rbla_stiff_bench";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];

  const std::vector<StiffCase> cases = rbla::stiff::stiff_cases();
  std::vector<Row> rows;
  int failures = 0;
  for (const auto& c : cases) {
    if (fast && c.slow) continue;
    if (!filter.empty() && c.name.find(filter) == std::string::npos) continue;
    if (!dump.empty()) {
      std::filesystem::create_directories(dump);
      std::ofstream(std::filesystem::path(dump) / (c.name + ".json")) << c.model.dump(1) << "\n";
    }
    rows.push_back(run_case(c));
    const Row& r = rows.back();
    failures += r.ok ? 0 : 1;
    std::cerr << (r.ok ? "ok   " : "FAIL ") << std::left << std::setw(48) << c.name << " " << std::setw(14) << r.verdict
              << " " << std::setw(14) << fmt(r.value, 10) << " err " << std::setw(10) << fmt(r.error, 2) << " ipm "
              << std::setw(4) << r.ipm_iterations << " " << fmt(r.seconds, 3) << " s " << r.note << "\n";
  }

  const std::vector<rbla::stiff::TwinCase> twins = rbla::stiff::twin_cases();
  std::vector<StiffCase> twin_holders(twins.size());
  std::vector<Row> twin_rows;
  for (std::size_t i = 0; i < twins.size(); ++i) {
    const auto& t = twins[i];
    if (fast && t.slow) continue;
    if (!filter.empty() && t.name.find(filter) == std::string::npos) continue;
    if (!dump.empty()) {
      std::filesystem::create_directories(dump);
      std::ofstream(std::filesystem::path(dump) / (t.name + ".json")) << t.model.dump(1) << "\n";
      std::ofstream(std::filesystem::path(dump) / (t.name + ".twin.json")) << t.twin.dump(1) << "\n";
    }
    twin_rows.push_back(run_twin(t, twin_holders[i]));
    const Row& r = twin_rows.back();
    failures += r.ok ? 0 : 1;
    std::cerr << (r.ok ? "ok   " : "FAIL ") << std::left << std::setw(48) << t.name << " " << std::setw(14) << r.verdict
              << " " << std::setw(14) << fmt(r.value, 10) << " err " << std::setw(10) << fmt(r.error, 2) << " ipm "
              << std::setw(4) << r.ipm_iterations << " " << fmt(r.seconds, 3) << " s " << r.note << "\n";
  }

  std::ostringstream md;
  md << "# Numerical stability: stiff and extreme cases\n\n"
     << "Generated by `bench/stiff/stiff_bench.cpp` (issue 7); do not edit by hand. Regenerate with\n\n"
     << "```sh\n"
     << "cmake -S bench/stiff -B build-stiff-bench -DCMAKE_BUILD_TYPE=Release\n"
     << "cmake --build build-stiff-bench -j2 --target rbla_stiff_bench\n"
     << command << "\n"
     << "```\n\n"
     << "- Machine: " << machine() << "\n"
     << "- rbla commit: `" << first_line_of("git -C " RBLA_SOURCE_DIR " rev-parse --short HEAD 2>/dev/null")
     << "`" << (first_line_of("git -C " RBLA_SOURCE_DIR " status --porcelain -- solver 2>/dev/null").empty() ? ""
                                                                                                         : " (solver/ modified)")
     << "\n"
     << "- Cases: " << rows.size() + twin_rows.size() << ", failures: " << failures << ". The GoogleTest suite `rbla_stiff_tests` "
     << "(`ctest -L stiff`) asserts the same cases except those marked *slow* below.\n"
     << "- Reference: a closed form evaluated from the case's inputs, never rbla's own output; the forms "
     << "([block], [column], [support], [slope], [pyramid], [settle]) are stated at the top of "
     << "`tests/stiff/stiff_cases.hpp`.\n"
     << "- α: the load multiplier, or the base reaction at collapse in kN for settlement cases. Relative error "
     << "= |α − reference| / |reference|; the accepted error is 1e-6 relative + 1e-7 absolute (the solver's "
     << "relative gap 1e-8 is of max(1, |α|)), 1e-5 relative + 1e-7 absolute for non-associative friction "
     << "(the scheme stops at a 1e-6 relative change of α). *ok* also requires the expected verdict, no NaN or "
     << "Inf in the result, and a converged non-associative scheme wherever 1e-6 |α| >= 1e-7 (below that the "
     << "requested change is under the solves' absolute accuracy). The test suite also reruns each "
     << "non-associative case at rbla's default tolerance (1e-4), which must converge where 1e-4 |α| >= 1e-7.\n"
     << "- IPM iterations: interior-point iterations, summed over the solves of the non-associative scheme "
     << "(number of solves in brackets). Time: model stage and analysis, wall clock, one run.\n";
  const std::string header =
      "| case | what varies | reference (source) | verdict | α | rel. error | IPM iterations | time (s) | ok |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  auto table_row = [&](const Row& r) {
    const StiffCase& c = *r.c;
    const std::string reference = c.expect == Expect::Collapse ? fmt(c.reference, 10) + " " + c.source
                                                                : std::string(rbla::stiff::to_string(c.expect)) + " " + c.source;
    md << "| `" << c.name << "`" << (c.slow ? " (slow)" : "") << " | " << escape(c.varies) << " | " << escape(reference)
       << " | " << r.verdict << " | " << fmt(r.value, 10) << " | " << fmt(r.error, 2) << " | " << r.ipm_iterations
       << (r.solves > 1 ? " (" + std::to_string(r.solves) + ")" : "") << " | " << fmt(r.seconds, 3) << " | "
       << (r.ok ? "yes" : "**no**") << (r.note.empty() ? "" : " " + escape(r.note)) << " |\n";
  };
  if (failures > 0) {
    md << "\n## Cases not ok\n\n";
    for (const auto* list : {&rows, &twin_rows}) {
      for (const Row& r : *list) {
        if (r.ok) continue;
        md << "- `" << r.c->name << "`: expected " << rbla::stiff::to_string(r.c->expect);
        if (r.c->expect == Expect::Collapse) md << " at " << fmt(r.c->reference, 10);
        md << ", got " << r.verdict;
        if (std::isfinite(r.value)) md << " at " << fmt(r.value, 10);
        md << (r.note.empty() ? "" : " (" + r.note + ")") << ".\n";
      }
    }
  }
  md << "\n## Closed forms\n\n" << header;
  for (const Row& r : rows) table_row(r);
  md << "\n## Well-conditioned twins\n\nThe reference is the twin's α (the same mechanics drawn at 1 m in kN, "
     << "or with the original unit weights); the accepted error is 1e-6 relative (associative) or 1e-5 "
     << "(non-associative, whose scheme stops at a 1e-6 relative change).\n\n"
     << header;
  for (const Row& r : twin_rows) table_row(r);
  if (markdown.empty()) {
    std::cout << md.str();
  } else {
    std::ofstream(markdown) << md.str();
    std::cerr << "wrote " << markdown << " (" << rows.size() + twin_rows.size() << " cases, " << failures << " failures)\n";
  }
  return failures == 0 ? 0 : 1;
}
