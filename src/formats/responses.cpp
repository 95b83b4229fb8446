#include "formats/responses.h"

#include <string_view>

#include "core/error.h"
#include "core/utf8.h"

namespace countershade {

std::optional<Question> question_from_name(const std::string& name) {
  for (int q = 0; q < kQuestionCount; ++q)
    if (name == kQuestionNames[q]) return Question(q);
  return std::nullopt;
}

const std::vector<std::string>& required_response_columns() {
  static const std::vector<std::string> columns = {"subject", "scene", "sigma", "question",
                                                   "lambda"};
  return columns;
}

const std::vector<std::string>& response_columns() {
  static const std::vector<std::string> columns = {
      "subject",      "scene",        "sigma",        "question",    "lambda",     "method",
      "lambda_step",  "lambda_index", "lambda_max",   "start_index", "repetition", "session",
      "trial",        "side",         "n_keypresses", "rt_ms",       "revision",   "timestamp_utc",
      "stimulus_set", "app_version",  "sequence"};
  return columns;
}

namespace {

class CsvParser {
 public:
  CsvParser(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  CsvTable parse() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);  // UTF-8 byte order mark
    for (size_t i = 0; i < text_.size(); ++i) {
      if (quoted_)
        quoted_char(i);
      else
        plain_char(i);
    }
    if (quoted_)
      throw_input_error(file_ + ": line " + std::to_string(row_line_),
                        "a quoted field is never closed");
    if (field_started_ || after_quote_ || !row_.empty()) end_row();
    return std::move(table_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw_input_error(
        file_ + ": line " + std::to_string(line_) + ", column " + std::to_string(row_.size() + 1),
        what);
  }
  void end_field() {
    // Names end up in results.json and the report, which hold only UTF-8 text.
    if (!is_utf8(field_)) fail("not UTF-8 text (save the file as UTF-8)");
    row_.push_back(std::move(field_));
    field_.clear();
    field_started_ = after_quote_ = false;
  }
  void end_row() {
    end_field();
    if (!(row_.size() == 1 && row_[0].empty())) {  // skip blank lines
      table_.rows.push_back(std::move(row_));
      table_.lines.push_back(row_line_);
    }
    row_.clear();
  }
  void quoted_char(size_t& i) {
    const char c = text_[i];
    if (c != '"') {
      if (c == '\n') ++line_;
      field_ += c;
    } else if (i + 1 < text_.size() && text_[i + 1] == '"') {
      field_ += '"';
      ++i;
    } else {
      quoted_ = false;
      after_quote_ = true;
    }
  }
  void plain_char(size_t& i) {
    const char c = text_[i];
    if (c == '"') {
      if (field_started_ || after_quote_)
        fail("a quote inside an unquoted field (quote the whole field and double the quote)");
      quoted_ = field_started_ = true;
    } else if (c == ',') {
      end_field();
    } else if (c == '\r' || c == '\n') {
      if (c == '\r' && i + 1 < text_.size() && text_[i + 1] == '\n') ++i;
      end_row();
      row_line_ = ++line_;
    } else {
      if (after_quote_) fail("text after a closing quote");
      field_ += c;
      field_started_ = true;
    }
  }

  std::string_view text_;
  const std::string& file_;
  CsvTable table_;
  std::vector<std::string> row_;
  std::string field_;
  size_t line_ = 1, row_line_ = 1;
  bool quoted_ = false, field_started_ = false, after_quote_ = false;
};

}  // namespace

CsvTable parse_csv(const std::string& text, const std::string& file) {
  return CsvParser(text, file).parse();
}

std::string csv_field(const std::string& value) {
  if (value.find_first_of(",\"\r\n") == std::string::npos) return value;
  std::string out = "\"";
  for (char c : value) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    line += csv_field(fields[i]);
  }
  return line + "\n";
}

}  // namespace countershade
