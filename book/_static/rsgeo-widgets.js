/* Names for the widgets' controls that screen readers announce (loaded by
   book/_ext/offline_book.py on pages with widgets only).

   The widget manager renders the widgets after the page has loaded, so a MutationObserver names
   what appears: a slider's handle (role="slider") gets its widget's description ("Generations"),
   and the Play widget's icon-only buttons their action. The names in the book's language are
   this script's data attributes (data-play, data-pause, data-stop, data-repeat, data-slider). */
(function () {
  "use strict";
  var script = document.currentScript;
  var names = (script && script.dataset) || {};
  var ACTIONS = {
    "play": "play", "pause": "pause", "stop": "stop", "retweet": "repeat", "repeat": "repeat"
  };

  function text(element) {
    return element ? (element.textContent || "").replace(/\s+/g, " ").trim() : "";
  }

  function nameSliders(root) {
    var handles = root.querySelectorAll('[role="slider"]:not([aria-label]):not([aria-labelledby])');
    handles.forEach(function (handle) {
      var widget = handle.closest(".widget-slider, .widget-inline-hbox, .jupyter-widgets");
      var label = widget && widget.querySelector(".widget-label");
      var name = text(label) || (label && label.getAttribute("title")) || names.slider || "Slider";
      handle.setAttribute("aria-label", name);
    });
  }

  function action(button) {
    var icon = button.querySelector('[class*="fa-"], svg[data-icon]');
    if (!icon) { return null; }
    var candidates = [icon.getAttribute("data-icon") || ""];
    (icon.getAttribute("class") || "").split(/\s+/).forEach(function (name) {
      if (name.indexOf("fa-") === 0) { candidates.push(name.slice(3)); }
    });
    for (var i = 0; i < candidates.length; i += 1) {
      if (ACTIONS[candidates[i]]) { return ACTIONS[candidates[i]]; }
    }
    return null;
  }

  function nameButtons(root) {
    // a button named here is named again when its icon changes (Play becomes Pause)
    var unnamed = "button.jupyter-button:not([aria-label]), button[data-rsgeo-named]";
    root.querySelectorAll(unnamed).forEach(function (button) {
      if (text(button)) { return; }
      var key = action(button);
      var name = (key && names[key]) || (!button.dataset.rsgeoNamed && button.title);
      if (name && button.getAttribute("aria-label") !== name) {
        button.setAttribute("aria-label", name);
        button.title = name;
        button.dataset.rsgeoNamed = "true";
      }
    });
  }

  var pending = false;
  function nameAll() {
    pending = false;
    nameSliders(document);
    nameButtons(document);
  }
  function schedule() {
    if (!pending) {
      pending = true;
      window.requestAnimationFrame(nameAll);
    }
  }

  function start() {
    nameAll();
    // only classes are observed (an icon that changes): naming a control (aria-label, title,
    // data-rsgeo-named) does not wake the observer again
    new MutationObserver(schedule).observe(document.body, {
      childList: true, subtree: true, attributes: true, attributeFilter: ["class"]
    });
  }
  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", start);
  } else {
    start();
  }
})();
