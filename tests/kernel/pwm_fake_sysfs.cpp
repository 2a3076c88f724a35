#include "tests/kernel/pwm_fake_sysfs.h"

#include <poll.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drivers/pwm/pwm_sysfs.h"

namespace xr::kernelrig {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
  return s;
}

void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// Plays the kernel: on a write to pwmchip0/export, creates pwm0 and watches
// it; `enable` appears last (by rename, so creating it is not a write), as
// the driver waits for it. Every later IN_MODIFY is recorded by file name.
class FakePwmKernel {
 public:
  explicit FakePwmKernel(const std::string& root)
      : chip_(root + "/pwmchip0"), fd_(inotify_init1(IN_CLOEXEC)) {
    ::mkdir(chip_.c_str(), 0755);
    put(chip_ + "/npwm", "2\n");
    put(chip_ + "/export", "");
    put(chip_ + "/unexport", "");
    inotify_add_watch(fd_, (chip_ + "/export").c_str(), IN_CLOSE_WRITE);
    thread_ = std::thread([this] { run(); });
  }
  ~FakePwmKernel() {
    stop_ = true;
    thread_.join();
    ::close(fd_);
  }
  std::vector<std::string> writes() {
    std::lock_guard<std::mutex> g(m_);
    return writes_;
  }
  std::string dutyAtPeriod() {
    std::lock_guard<std::mutex> g(m_);
    return dutyAtPeriod_;
  }
  std::string enableAtPolarity() {
    std::lock_guard<std::mutex> g(m_);
    return enableAtPolarity_;
  }

 private:
  void exportChannel() {
    const std::string dir = chip_ + "/pwm0";
    ::mkdir(dir.c_str(), 0755);
    for (const char* a : {"period", "duty_cycle", "polarity"})
      put(dir + "/" + a, std::string(a) == "polarity" ? "normal\n" : "0\n");
    put(chip_ + "/.enable", "0\n");
    pwmWatch_ = inotify_add_watch(fd_, dir.c_str(), IN_MODIFY);
    ::rename((chip_ + "/.enable").c_str(), (dir + "/enable").c_str());
  }
  void run() {
    alignas(inotify_event) char buf[4096];
    while (!stop_) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      for (ssize_t off = 0; off < n;) {
        const auto* ev = reinterpret_cast<const inotify_event*>(buf + off);
        off += static_cast<ssize_t>(sizeof(inotify_event) + ev->len);
        if (ev->wd != pwmWatch_) {
          if (slurp(chip_ + "/export") == "0" && pwmWatch_ < 0) exportChannel();
          continue;
        }
        std::lock_guard<std::mutex> g(m_);
        const std::string name = ev->len ? ev->name : "";
        // pwrite then ftruncate of one value: one write, not two.
        if (writes_.empty() || writes_.back() != name) writes_.push_back(name);
        // The kernel refuses a period below the duty and a polarity change
        // while enabled: note the other attributes when these are written.
        if (name == "period") dutyAtPeriod_ = slurp(chip_ + "/pwm0/duty_cycle");
        if (name == "polarity") enableAtPolarity_ = slurp(chip_ + "/pwm0/enable");
      }
    }
  }
  std::string chip_;
  int fd_;
  int pwmWatch_ = -1;
  std::atomic<bool> stop_{false};
  std::mutex m_;
  std::vector<std::string> writes_;
  std::string dutyAtPeriod_ = "unwritten", enableAtPolarity_ = "unwritten";
  std::thread thread_;
};

int indexOf(const std::vector<std::string>& v, const std::string& s) {
  for (size_t i = 0; i < v.size(); ++i)
    if (v[i] == s) return static_cast<int>(i);
  return -1;
}

}  // namespace

int pwmCheck(const std::string& root) {
  int fails = 0;
  auto check = [&](bool ok, const std::string& what) {
    std::cout << (ok ? "pwm ok: " : "pwm FAIL: ") << what << std::endl;
    fails += ok ? 0 : 1;
  };
  const std::string dir = root + "/pwmchip0/pwm0/";
  std::vector<std::string> openOrder, all;
  std::string dutyAtPeriod, enableAtPolarity;
  {
    FakePwmKernel kernel(root);
    PwmSysfs pwm;
    const bool opened = pwm.open(root, 0, 0, 400.0, false);
    check(opened, "open exported pwm0 via pwmchip0/export" + (opened ? "" : ": " + pwm.error()));
    if (!opened) return 1;
    check(slurp(dir + "period") == "2500000",
          "period 2500000 ns at 400 Hz (got " + slurp(dir + "period") + ")");
    check(slurp(dir + "duty_cycle") == "0" && slurp(dir + "enable") == "0", "opened with duty 0, disabled");
    ::usleep(200'000);  // let the watcher catch up before reading its record
    openOrder = kernel.writes();
    dutyAtPeriod = kernel.dutyAtPeriod();
    enableAtPolarity = kernel.enableAtPolarity();
    pwm.setDutyPercent(50.0);
    pwm.setEnabled(true);
    check(slurp(dir + "duty_cycle") == "1250000" && slurp(dir + "enable") == "1",
          "50 % -> duty 1250000, enable 1");
    check(pwm.safeStateWriter().driveSafe(), "fatal-path safe state written");
    check(slurp(dir + "duty_cycle") == "0" && slurp(dir + "enable") == "0", "safe state: duty 0, enable 0");
    ::usleep(200'000);
    all = kernel.writes();
  }
  std::string seq;
  for (const auto& w : all) seq += w + " ";
  std::cout << "pwm: attribute writes in order: " << seq << std::endl;
  check(indexOf(openOrder, "period") >= 0 && dutyAtPeriod == "0",
        "period written while duty_cycle is 0 (the kernel refuses duty > period; got " + dutyAtPeriod + ")");
  check(enableAtPolarity == "0", "polarity written while disabled (got enable " + enableAtPolarity + ")");
  // After open: 50 % duty, enable, then the safe state's duty 0, enable 0.
  const auto firstAfterOpen = all.begin() + static_cast<long>(std::min(openOrder.size(), all.size()));
  const std::vector<std::string> after(firstAfterOpen, all.end());
  const std::vector<std::string> want{"duty_cycle", "enable", "duty_cycle", "enable"};
  check(after == want, "after open: duty_cycle, enable, then the safe state's duty_cycle, enable");
  return fails == 0 ? 0 : 1;
}

}  // namespace xr::kernelrig
