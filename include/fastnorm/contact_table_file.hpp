#pragma once
/// @file contact_table_file.hpp
/// The binary file of a ContactTable (docs/tables.md §4, "The export file"), what
/// `fastnorm-table export STORE OUT.fntable` writes and a time loop reads at start-up.
/// Little-endian, in order:
///
///     "FNTABLE\0"                          8 bytes
///     version = 2                          uint32
///     pairs, shifts, yaws, loads, outputs  uint32 × 5
///     lateral_shift_m, yaw_rad, load_n     float64 × shifts, yaws, loads
///     pair names, output names, units      each: uint32 length, then that many UTF-8 bytes
///     values                               float64 × pairs·loads·yaws·shifts·outputs (ContactTable's layout)
///     topology                             int32 × pairs·loads·yaws·shifts
///     measured                             uint32: 1 if measured derivatives follow, else 0
///     measured_shift_derivatives           float64 × (values' count) if measured
///
/// and nothing after. Version 1, without the last two, is read too. Reading checks all of it
/// and names what is wrong.

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

#include "fastnorm/contact_table.hpp"
#include "fastnorm/error.hpp"

namespace fastnorm {

namespace detail {

constexpr char contact_table_magic[8] = {'F', 'N', 'T', 'A', 'B', 'L', 'E', '\0'};
constexpr std::uint32_t contact_table_version = 2;

inline bool host_is_little_endian() {
  const std::uint32_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

/// Reads the numbers of a contact-table file, naming the file and the part that is missing.
class TableFileReader {
 public:
  explicit TableFileReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    FASTNORM_CHECK(in_.good(), "cannot open contact table '" + path + "'");
  }

  template <typename Number>
  std::vector<Number> numbers(std::size_t count, const std::string& what) {
    static_assert(std::is_arithmetic<Number>::value, "numbers of the file");
    std::vector<Number> read(count);
    bytes(reinterpret_cast<char*>(read.data()), count * sizeof(Number), what);
    return read;
  }

  std::uint32_t count(const std::string& what) { return numbers<std::uint32_t>(1, what)[0]; }

  std::vector<std::string> texts(std::size_t count, const std::string& what) {
    std::vector<std::string> read(count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t length = this->count(what + " " + std::to_string(i) + " (its length)");
      FASTNORM_CHECK(length <= 4096, path_ + ": " + describe(what + " " + std::to_string(i) + " is too long", length));
      read[i].resize(length);
      bytes(&read[i][0], length, what + " " + std::to_string(i));
    }
    return read;
  }

  void bytes(char* into, std::size_t count, const std::string& what) {
    if (count == 0) return;
    in_.read(into, static_cast<std::streamsize>(count));
    FASTNORM_CHECK(in_.good(), "contact table '" + path_ + "' ends before its " + what);
  }

  void expect_end() {
    FASTNORM_CHECK(in_.peek() == std::char_traits<char>::eof(),
                   "contact table '" + path_ + "' has bytes after its last part");
  }

 private:
  std::string path_;
  std::ifstream in_;
};

inline void write_texts(std::ofstream& out, const std::vector<std::string>& texts) {
  for (const std::string& text : texts) {
    const auto length = static_cast<std::uint32_t>(text.size());
    out.write(reinterpret_cast<const char*>(&length), sizeof length);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  }
}

template <typename Number>
void write_numbers(std::ofstream& out, const std::vector<Number>& numbers) {
  out.write(reinterpret_cast<const char*>(numbers.data()), static_cast<std::streamsize>(numbers.size() * sizeof(Number)));
}

}  // namespace detail

/// Reads a contact table written by write_contact_table (or by fastnorm-table export).
/// @throws fastnorm::invalid_argument naming the file and what is wrong: not a table, another
/// version, cut short, trailing bytes, or contents ContactTable refuses
inline ContactTable read_contact_table(const std::string& path) {
  FASTNORM_CHECK(detail::host_is_little_endian(), "contact tables are read on little-endian machines only");
  detail::TableFileReader file(path);
  char magic[8] = {};
  file.bytes(magic, sizeof magic, "header");
  FASTNORM_CHECK(std::memcmp(magic, detail::contact_table_magic, sizeof magic) == 0,
                 "'" + path + "' is not a fastnorm contact table (no FNTABLE header)");
  const std::uint32_t version = file.count("version");
  FASTNORM_CHECK(version == 1 || version == detail::contact_table_version,
                 describe("contact table '" + path + "' is of another format version than 1 or 2", version));
  const std::uint32_t pairs = file.count("pair count");
  const std::uint32_t shifts = file.count("shift count");
  const std::uint32_t yaws = file.count("yaw count");
  const std::uint32_t loads = file.count("load count");
  const std::uint32_t outputs = file.count("output count");
  // Sizes a table of 2^31 numbers cannot exceed: guards the products below and the reads.
  const double numbers = double(pairs) * shifts * yaws * loads * (outputs + 1.0);
  FASTNORM_CHECK(numbers < 2147483648.0, describe("contact table '" + path + "' claims too many numbers", numbers));
  TableAxes axes;
  axes.lateral_shift_m = file.numbers<double>(shifts, "lateral shifts");
  axes.yaw_rad = file.numbers<double>(yaws, "yaws");
  axes.load_n = file.numbers<double>(loads, "loads");
  std::vector<std::string> pair_names = file.texts(pairs, "pair name");
  std::vector<std::string> output_names = file.texts(outputs, "output name");
  std::vector<std::string> output_units = file.texts(outputs, "output unit");
  const std::size_t cases = std::size_t(pairs) * shifts * yaws * loads;
  std::vector<double> values = file.numbers<double>(cases * outputs, "values");
  std::vector<std::int32_t> topology = file.numbers<std::int32_t>(cases, "topology");
  std::vector<double> measured;
  if (version >= 2) {
    const std::uint32_t has_measured = file.count("measured-derivatives flag");
    FASTNORM_CHECK(has_measured <= 1,
                   describe("contact table '" + path + "': the measured-derivatives flag must be 0 or 1", has_measured));
    if (has_measured == 1) measured = file.numbers<double>(cases * outputs, "measured derivatives");
  }
  file.expect_end();
  try {
    return ContactTable(std::move(axes), std::move(pair_names), std::move(output_names), std::move(output_units),
                        std::move(values), std::move(topology), std::move(measured));
  } catch (const invalid_argument& error) {  // the same message, with the file named after "fastnorm: "
    throw invalid_argument("fastnorm: contact table '" + path + "': " + std::string(error.what()).substr(10));
  }
}

/// Writes `table` to `path` in the format above.
/// @throws fastnorm::invalid_argument if the file cannot be written
inline void write_contact_table(const ContactTable& table, const std::string& path) {
  FASTNORM_CHECK(detail::host_is_little_endian(), "contact tables are written on little-endian machines only");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  FASTNORM_CHECK(out.good(), "cannot write contact table '" + path + "'");
  out.write(detail::contact_table_magic, sizeof detail::contact_table_magic);
  const TableAxes& axes = table.axes();
  detail::write_numbers(out, std::vector<std::uint32_t>{
                                 detail::contact_table_version, static_cast<std::uint32_t>(table.pairs()),
                                 static_cast<std::uint32_t>(axes.lateral_shift_m.size()),
                                 static_cast<std::uint32_t>(axes.yaw_rad.size()),
                                 static_cast<std::uint32_t>(axes.load_n.size()),
                                 static_cast<std::uint32_t>(table.outputs())});
  detail::write_numbers(out, axes.lateral_shift_m);
  detail::write_numbers(out, axes.yaw_rad);
  detail::write_numbers(out, axes.load_n);
  detail::write_texts(out, table.pair_names());
  detail::write_texts(out, table.output_names());
  detail::write_texts(out, table.output_units());
  detail::write_numbers(out, table.values());
  detail::write_numbers(out, table.topology());
  const std::vector<double>& measured = table.measured_shift_derivatives();
  detail::write_numbers(out, std::vector<std::uint32_t>{measured.empty() ? 0u : 1u});
  detail::write_numbers(out, measured);
  out.flush();
  FASTNORM_CHECK(out.good(), "writing contact table '" + path + "' failed");
}

}  // namespace fastnorm
