// CBF (Conic Benchmark Format v3, Friberg 2016, https://cblib.zib.de/doc/format3.pdf) and
// free-format MPS writers; a CBF reader for the subset written here.

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
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

namespace {

/// The CBF subset read_cbf accepts, one section at a time. Every count and index is checked as
/// it is read (a bad file is a ConicSetupError naming the line, never another exception), and
/// nothing is allocated for a declared size before it has been checked against the limits.
class CbfReader {
 public:
  CbfReader(std::istream& in, const CbfLimits& limits) : in_(in), limits_(limits) {}

  ConicProblem read() {
    std::string line;
    while (next_line(line)) {
      if (line == "VER") {
        if (integer(expect_line("version"), "version") > 3) throw fail("unsupported CBF version");
      } else if (line == "OBJSENSE") {
        const std::string sense = expect_line("OBJSENSE value");
        if (sense != "MIN" && sense != "MAX") throw fail("unknown OBJSENSE " + quoted(sense));
        sense_ = sense == "MAX" ? -1.0 : 1.0;
      } else if (line == "VAR") {
        read_var();
      } else if (line == "CON") {
        read_con();
      } else if (line == "OBJACOORD" || line == "BCOORD") {
        read_vector(line == "OBJACOORD" ? c_entries_ : b_entries_, line);
      } else if (line == "ACOORD") {
        read_matrix();
      } else if (line == "OBJBCOORD") {
        if (number(expect_line("OBJBCOORD value"), "OBJBCOORD") != 0.0)
          throw fail("a constant objective term is not supported");
      } else {
        throw fail("unsupported keyword " + quoted(line));
      }
    }
    return assemble();
  }

 private:
  /// A field of the file as messages show it: at most 40 bytes, printable ASCII only.
  static std::string quoted(const std::string& text) {
    std::string out = "'";
    for (std::size_t k = 0; k < text.size() && k < 40; ++k) {
      const unsigned char c = static_cast<unsigned char>(text[k]);
      out += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
    }
    return out + (text.size() > 40 ? "...'" : "'");
  }

  ConicSetupError fail(const std::string& what) const {
    return ConicSetupError("read_cbf: line " + std::to_string(line_number_) + ": " + what);
  }

  /// The next line that is neither blank nor a comment ('#'), trimmed.
  bool next_line(std::string& line) {
    while (std::getline(in_, line)) {
      ++line_number_;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      const auto last = line.find_last_not_of(" \t\r");
      line = line.substr(first, last - first + 1);
      return true;
    }
    return false;
  }

  std::string expect_line(const std::string& what) {
    std::string line;
    if (!next_line(line)) throw fail("the file ends before the " + what);
    return line;
  }

  /// Whitespace-separated fields of a line; exactly `count` of them.
  std::vector<std::string> fields(const std::string& line, std::size_t count, const std::string& what) {
    std::istringstream stream(line);
    std::vector<std::string> out;
    std::string field;
    while (stream >> field) out.push_back(field);
    if (out.size() != count) throw fail(what + ": expected " + std::to_string(count) + " fields in " + quoted(line));
    return out;
  }

  long long integer(const std::string& text, const std::string& what) const {
    errno = 0;
    char* end = nullptr;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE) throw fail(what + ": " + quoted(text) + " is not an integer");
    return value;
  }

  long long count(const std::string& text, const std::string& what, long long max) const {
    const long long value = integer(text, what);
    if (value < 0 || value > max) {
      throw fail(what + " " + std::to_string(value) + " is out of range [0, " + std::to_string(max) + "]");
    }
    return value;
  }

  double number(const std::string& text, const std::string& what) const {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
      throw fail(what + ": " + quoted(text) + " is not a finite number");
    }
    return value;
  }

  /// A VAR or CON section: "SIZE COUNT", then COUNT lines "TYPE SIZE_k" that must cover SIZE
  /// exactly; `take(type, size_k, k)` accepts a cone (false: not supported). Returns SIZE.
  template <class Take>
  long long read_cones(const std::string& section, const std::string& what, long long max, Take take) {
    const auto header = fields(expect_line(section + " header"), 2, section + " header");
    const long long size = count(header[0], "number of " + what, max);
    const long long num_cones = count(header[1], "number of cones", size);
    long long covered = 0;
    for (long long k = 0; k < num_cones; ++k) {
      const std::string line = expect_line(section + " cone list");
      const auto cone = fields(line, 2, section + " cone");
      const long long cone_size = count(cone[1], "cone size", size - covered);
      if (!take(cone[0], cone_size, k)) throw fail(section + " cone " + quoted(line) + " not supported");
      covered += cone_size;
    }
    if (covered != size) {
      throw fail("the " + section + " cones cover " + std::to_string(covered) + " of " + std::to_string(size) + " " + what);
    }
    return size;
  }

  /// Variables: at most one leading L+, then Q cones.
  void read_var() {
    if (n_ >= 0) throw fail("a second VAR section");
    n_ = read_cones("VAR", "variables", limits_.max_variables, [&](const std::string& type, long long size, long long k) {
      if (type == "L+" && k == 0) p_.cones.num_nonneg = size;
      else if (type == "Q") p_.cones.soc_dims.push_back(size);
      else return false;
      return true;
    });
  }

  /// Constraints: L= only.
  void read_con() {
    if (m_ >= 0) throw fail("a second CON section");
    m_ = read_cones("CON", "rows", limits_.max_constraints,
                    [](const std::string& type, long long, long long) { return type == "L="; });
  }

  /// OBJACOORD (indices into the variables) or BCOORD (into the rows): "count", then "index value".
  void read_vector(std::vector<std::pair<Eigen::Index, double>>& entries, const std::string& keyword) {
    const bool objective = keyword == "OBJACOORD";
    const long long size = objective ? n_ : m_;
    if (size < 0) throw fail(keyword + " before " + (objective ? "VAR" : "CON"));
    const long long num = count(expect_line(keyword + " count"), keyword + " count", limits_.max_nonzeros);
    for (long long k = 0; k < num; ++k) {
      const auto entry = fields(expect_line(keyword + " entries"), 2, keyword + " entry");
      const long long index = count(entry[0], keyword + " index", size - 1);
      entries.emplace_back(index, number(entry[1], keyword + " value"));
    }
  }

  void read_matrix() {
    if (n_ < 0 || m_ < 0) throw fail("ACOORD before VAR and CON");
    const long long num = count(expect_line("ACOORD count"), "ACOORD count", limits_.max_nonzeros - static_cast<long long>(triplets_.size()));
    for (long long k = 0; k < num; ++k) {
      const auto entry = fields(expect_line("ACOORD entries"), 3, "ACOORD entry");
      const long long row = count(entry[0], "ACOORD row", m_ - 1);
      const long long col = count(entry[1], "ACOORD column", n_ - 1);
      triplets_.emplace_back(row, col, number(entry[2], "ACOORD value"));
    }
  }

  ConicProblem assemble() {
    if (n_ < 0) throw fail("no VAR section");
    const Eigen::Index m = std::max<long long>(m_, 0);
    p_.A.resize(m, n_);
    p_.A.setFromTriplets(triplets_.begin(), triplets_.end());
    p_.A.makeCompressed();
    p_.b = Eigen::VectorXd::Zero(m);
    p_.c = Eigen::VectorXd::Zero(n_);
    for (const auto& [i, v] : b_entries_) p_.b[i] -= v;  // A x + b_cbf = 0  ⇔  A x = −b_cbf
    for (const auto& [j, v] : c_entries_) p_.c[j] += sense_ * v;
    const auto messages = p_.validate();
    if (!messages.empty()) throw ConicSetupError::from_messages("read_cbf: invalid problem", messages);
    return std::move(p_);
  }

  std::istream& in_;
  CbfLimits limits_;
  long line_number_ = 0;
  ConicProblem p_;
  long long n_ = -1, m_ = -1;
  double sense_ = 1.0;
  std::vector<Eigen::Triplet<double>> triplets_;
  std::vector<std::pair<Eigen::Index, double>> c_entries_, b_entries_;
};

}  // namespace

ConicProblem read_cbf(std::istream& in, const CbfLimits& limits) { return CbfReader(in, limits).read(); }

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
