#ifndef rbc_ifem_base_csv_h
#define rbc_ifem_base_csv_h

#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace rbc_ifem
{
  /**
   * One row of a CSV table: values streamed in with operator<<, separated by
   * commas, numbers with ten significant digits. Every table of results
   * formats its numbers this way (timing.csv, of wall times, has six).
   */
  class CsvRow
  {
  public:
    CsvRow()
    {
      text << std::setprecision(10);
    }

    template <typename Value>
    CsvRow &
    operator<<(const Value &value)
    {
      text << separator << value;
      separator = ",";
      return *this;
    }

    std::string
    str() const
    {
      return text.str();
    }

  private:
    std::ostringstream text;
    const char        *separator = "";
  };

  /// A row from @p values, in order.
  template <typename... Values>
  std::string
  csv_row(const Values &...values)
  {
    CsvRow row;
    (row << ... << values);
    return row.str();
  }

  /**
   * A CSV table: one header row and the rows added so far. A run keeps its
   * tables whole and rewrites each file from them (write()), so a file is
   * always complete, and a checkpoint can carry them (serialize()).
   */
  class CsvTable
  {
  public:
    CsvTable() = default;

    /// A table with the column names @p header ("a,b,c").
    explicit CsvTable(const std::string &header);

    void
    set_header(const std::string &header);

    void
    add_row(const std::string &row);

    /// Add the row of @p values.
    template <typename... Values>
    void
    add(const Values &...values)
    {
      add_row(csv_row(values...));
    }

    /// The table as @p path, complete or not at all (write_file_atomically()).
    void
    write(const std::string &path) const;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &header &rows;
    }

  private:
    std::string              header;
    std::vector<std::string> rows;
  };
} // namespace rbc_ifem

#endif
