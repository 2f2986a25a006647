// CBF (Conic Benchmark Format v3, Friberg 2016, https://cblib.zib.de/doc/format3.pdf) and
// free-format MPS writers; a CBF reader for the subset written here.

#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "rbla/conic/io.hpp"

namespace rbla::conic {

namespace {

std::ofstream open_for_writing(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw ConicSetupError("cannot open '" + path + "' for writing");
  out << std::setprecision(17);
  return out;
}

}  // namespace

void write_cbf(const ConicProblem& p, std::ostream& out) {
  const auto messages = p.validate();
  if (!messages.empty())
    throw ConicSetupError::from_messages("write_cbf: invalid problem", messages);
  const auto precision = out.precision(17);
  const Eigen::Index m = p.A.rows(), n = p.A.cols();
  const std::size_t num_cones = (p.cones.num_nonneg > 0 ? 1 : 0) + p.cones.soc_dims.size();
  out << "# written by rbla::conic::write_cbf: min c'x s.t. A x - b = 0, x in K\n";
  out << "VER\n3\n\nOBJSENSE\nMIN\n\n";
  out << "VAR\n" << n << ' ' << num_cones << '\n';
  if (p.cones.num_nonneg > 0) out << "L+ " << p.cones.num_nonneg << '\n';
  for (Eigen::Index q : p.cones.soc_dims) out << "Q " << q << '\n';
  out << '\n';
  if (m > 0) out << "CON\n" << m << " 1\nL= " << m << "\n\n";
  long nnz_c = 0;
  for (Eigen::Index j = 0; j < n; ++j) nnz_c += p.c[j] != 0.0;
  if (nnz_c > 0) {
    out << "OBJACOORD\n" << nnz_c << '\n';
    for (Eigen::Index j = 0; j < n; ++j) {
      if (p.c[j] != 0.0) out << j << ' ' << p.c[j] << '\n';
    }
    out << '\n';
  }
  long nnz_A = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, j); it; ++it)
      nnz_A += it.value() != 0.0;
  }
  if (nnz_A > 0) {
    out << "ACOORD\n" << nnz_A << '\n';
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, j); it; ++it) {
        if (it.value() != 0.0) out << it.row() << ' ' << j << ' ' << it.value() << '\n';
      }
    }
    out << '\n';
  }
  long nnz_b = 0;
  for (Eigen::Index i = 0; i < m; ++i) nnz_b += p.b[i] != 0.0;
  if (nnz_b > 0) {
    out << "BCOORD\n" << nnz_b << '\n';  // CBF: A x + b ∈ K, so the constant is −b
    for (Eigen::Index i = 0; i < m; ++i) {
      if (p.b[i] != 0.0) out << i << ' ' << -p.b[i] << '\n';
    }
  }
  out.precision(precision);
}

void write_cbf(const ConicProblem& problem, const std::string& path) {
  auto out = open_for_writing(path);
  write_cbf(problem, out);
  if (!out) throw ConicSetupError("write to '" + path + "' failed");
}

ConicProblem read_cbf(std::istream& in) {
  auto fail = [](const std::string& what) -> ConicSetupError {
    return ConicSetupError("read_cbf: " + what);
  };
  // Keywords followed by their data; '#' starts a comment line.
  auto next_line = [&in](std::string& line) {
    while (std::getline(in, line)) {
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      line = line.substr(first);
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      return true;
    }
    return false;
  };
  ConicProblem p;
  Eigen::Index n = -1, m = 0;
  double sense = 1.0;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<std::pair<Eigen::Index, double>> c_entries, b_entries;
  std::string line;
  while (next_line(line)) {
    if (line == "VER") {
      if (!next_line(line)) throw fail("missing version");
      if (std::stoi(line) > 3) throw fail("unsupported CBF version " + line);
    } else if (line == "OBJSENSE") {
      if (!next_line(line)) throw fail("missing OBJSENSE value");
      if (line == "MAX")
        sense = -1.0;
      else if (line != "MIN")
        throw fail("unknown OBJSENSE " + line);
    } else if (line == "VAR") {
      if (!next_line(line)) throw fail("missing VAR header");
      std::istringstream header(line);
      std::size_t count = 0;
      header >> n >> count;
      bool in_socs = false;
      for (std::size_t k = 0; k < count; ++k) {
        if (!next_line(line)) throw fail("truncated VAR section");
        std::istringstream cone(line);
        std::string type;
        Eigen::Index size = 0;
        cone >> type >> size;
        if (type == "L+" && !in_socs && p.cones.num_nonneg == 0) {
          p.cones.num_nonneg = size;
        } else if (type == "Q") {
          p.cones.soc_dims.push_back(size);
          in_socs = true;
        } else {
          throw fail("VAR cone '" + line + "' not supported (only one leading L+, then Q)");
        }
      }
    } else if (line == "CON") {
      if (!next_line(line)) throw fail("missing CON header");
      std::istringstream header(line);
      std::size_t count = 0;
      header >> m >> count;
      for (std::size_t k = 0; k < count; ++k) {
        if (!next_line(line)) throw fail("truncated CON section");
        if (line.rfind("L=", 0) != 0) throw fail("CON cone '" + line + "' not supported (only L=)");
      }
    } else if (line == "OBJACOORD" || line == "BCOORD") {
      auto& entries = line == "OBJACOORD" ? c_entries : b_entries;
      if (!next_line(line)) throw fail("missing count");
      const long count = std::stol(line);
      for (long k = 0; k < count; ++k) {
        if (!next_line(line)) throw fail("truncated coordinate list");
        std::istringstream entry(line);
        Eigen::Index i = 0;
        double v = 0;
        entry >> i >> v;
        entries.push_back({i, v});
      }
    } else if (line == "ACOORD") {
      if (!next_line(line)) throw fail("missing ACOORD count");
      const long count = std::stol(line);
      for (long k = 0; k < count; ++k) {
        if (!next_line(line)) throw fail("truncated ACOORD");
        std::istringstream entry(line);
        Eigen::Index i = 0, j = 0;
        double v = 0;
        entry >> i >> j >> v;
        triplets.emplace_back(i, j, v);
      }
    } else if (line == "OBJBCOORD") {
      if (!next_line(line)) throw fail("missing OBJBCOORD value");
      if (std::stod(line) != 0.0) throw fail("a constant objective term is not supported");
    } else {
      throw fail("unsupported keyword '" + line + "'");
    }
  }
  if (n < 0) throw fail("no VAR section");
  p.A.resize(m, n);
  for (const auto& t : triplets) {
    if (t.row() < 0 || t.row() >= m || t.col() < 0 || t.col() >= n)
      throw fail("ACOORD index out of range");
  }
  p.A.setFromTriplets(triplets.begin(), triplets.end());
  p.A.makeCompressed();
  p.b = Eigen::VectorXd::Zero(m);
  p.c = Eigen::VectorXd::Zero(n);
  for (const auto& [i, v] : b_entries) {
    if (i < 0 || i >= m) throw fail("BCOORD index out of range");
    p.b[i] -= v;  // A x + b_cbf = 0  ⇔  A x = −b_cbf
  }
  for (const auto& [j, v] : c_entries) {
    if (j < 0 || j >= n) throw fail("OBJACOORD index out of range");
    p.c[j] += sense * v;
  }
  const auto messages = p.validate();
  if (!messages.empty())
    throw ConicSetupError::from_messages("read_cbf: invalid problem", messages);
  return p;
}

ConicProblem read_cbf_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConicSetupError("cannot open '" + path + "'");
  return read_cbf(in);
}

void write_mps(const ConicProblem& p, std::ostream& out) {
  const auto messages = p.validate();
  if (!messages.empty())
    throw ConicSetupError::from_messages("write_mps: invalid problem", messages);
  if (!p.cones.soc_dims.empty())
    throw ConicSetupError("write_mps: MPS cannot express second-order cones");
  const auto precision = out.precision(17);
  const Eigen::Index m = p.A.rows(), n = p.A.cols();
  out << "NAME rbla_conic\nROWS\n N obj\n";
  for (Eigen::Index i = 0; i < m; ++i) out << " E R" << i << '\n';
  out << "COLUMNS\n";
  for (Eigen::Index j = 0; j < n; ++j) {
    // The objective entry is always written (even 0) so that every column exists.
    out << " X" << j << " obj " << p.c[j] << '\n';
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.A, j); it; ++it) {
      if (it.value() != 0.0) out << " X" << j << " R" << it.row() << ' ' << it.value() << '\n';
    }
  }
  out << "RHS\n";
  for (Eigen::Index i = 0; i < m; ++i) {
    if (p.b[i] != 0.0) out << " rhs R" << i << ' ' << p.b[i] << '\n';
  }
  out << "ENDATA\n";  // no BOUNDS section: MPS's default bounds are [0, +inf)
  out.precision(precision);
}

void write_mps(const ConicProblem& problem, const std::string& path) {
  auto out = open_for_writing(path);
  write_mps(problem, out);
  if (!out) throw ConicSetupError("write to '" + path + "' failed");
}

}  // namespace rbla::conic
