// CGAL's Protect_edges_sizing_field writes "Warning : features protection has
// reached maximal number of loops. It might result in a crash." to std::cerr
// when balls of two close polylines keep intersecting. Nothing crashes (the
// refinement is retried without those features) and the report says it
// (protection.protecting_balls_intersect), so the command line drops those
// two lines; every other line written to std::cerr passes through. The
// library itself never redirects the process's streams: the CLI owns them.
#pragma once

#include <iostream>
#include <streambuf>
#include <string>

namespace sharpmesh::cli {

class CgalMessageFilter : public std::streambuf {
 public:
  CgalMessageFilter() : target_(std::cerr.rdbuf(this)) {}
  ~CgalMessageFilter() override {
    flush_line();
    std::cerr.rdbuf(target_);
  }
  CgalMessageFilter(const CgalMessageFilter&) = delete;
  CgalMessageFilter& operator=(const CgalMessageFilter&) = delete;

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    line_.push_back(traits_type::to_char_type(c));
    if (c == '\n') flush_line();
    return c;
  }
  // std::cerr flushes after every insertion; a line is judged whole, so a
  // partial one waits for its newline.
  int sync() override { return target_->pubsync(); }

 private:
  void flush_line() {
    if (line_.empty()) return;
    const bool warning = line_.find("features protection has reached maximal") != std::string::npos;
    const bool follow_up = dropped_warning_ && line_.find("It might result in a crash") != std::string::npos;
    dropped_warning_ = warning;
    if (!warning && !follow_up) target_->sputn(line_.data(), static_cast<std::streamsize>(line_.size()));
    line_.clear();
  }

  std::streambuf* target_;
  std::string line_;
  bool dropped_warning_ = false;
};

}  // namespace sharpmesh::cli
