#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>

namespace rbc_ifem
{
  CsvTable::CsvTable(const std::string &header)
    : header(header)
  {}

  void
  CsvTable::set_header(const std::string &new_header)
  {
    header = new_header;
  }

  void
  CsvTable::add_row(const std::string &row)
  {
    rows.push_back(row);
  }

  void
  CsvTable::write(const std::string &path) const
  {
    write_file_atomically(path, [&](std::ostream &out) {
      out << header << '\n';
      for (const std::string &row : rows)
        out << row << '\n';
    });
  }
} // namespace rbc_ifem
