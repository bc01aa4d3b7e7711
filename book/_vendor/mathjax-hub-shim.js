// The ipywidgets HTML manager typesets labels with MathJax 2's MathJax.Hub.Queue whenever
// window.MathJax exists; the book loads MathJax 3, which has no Hub. This maps the one call
// the widgets make onto MathJax 3's typesetPromise.
(function () {
  function install() {
    if (window.MathJax && !window.MathJax.Hub) {
      window.MathJax.Hub = {
        Queue: function (job) {
          var element = job && job[2];
          if (element && window.MathJax.typesetPromise) {
            window.MathJax.typesetPromise([element]);
          }
        }
      };
    }
  }
  install();
  document.addEventListener("DOMContentLoaded", install);
})();
