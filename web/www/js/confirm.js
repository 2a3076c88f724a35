// A confirmation before a command that changes what the alternator does.
// Resolves true only on an explicit "Confirm".
export function confirmAction(text, okLabel = "Confirm") {
  const dlg = document.getElementById("confirm-dialog");
  document.getElementById("confirm-text").textContent = text;
  document.getElementById("confirm-ok").textContent = okLabel;
  dlg.returnValue = "";
  return new Promise((resolve) => {
    dlg.addEventListener("close", () => resolve(dlg.returnValue === "ok"), { once: true });
    dlg.showModal();
    document.getElementById("confirm-cancel").focus();  // a stray Enter cancels
  });
}

// What each dangerous command asks; args are the already checked arguments.
export const CONFIRM_TEXT = {
  off: () => ["Switch the regulator OFF? The alternator stops charging until you press Auto.", "Switch off"],
  manual: (a) => [`Switch to MANUAL with a fixed field of ${a.duty} %? Nothing regulates the battery voltage in manual: watch it yourself.`, "Go manual"],
  limp_home: () => ["Start LIMP HOME? A fixed low field with most sensors ignored — only to get home with a failed sensor.", "Start limp home"],
  set_soc: (a) => [`Set the state of charge to ${a.soc_pct} %? The charge stages use it.`, "Set SoC"],
};
